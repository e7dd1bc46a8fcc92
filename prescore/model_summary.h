// What `shatter info` says about a model: pieces, tets per piece, constraints, piece pairs,
// mass, volume, collision parts, whether each piece is one connected component (recomputed
// from the tets, not trusted from the file), and the model-size report.
#pragma once

#include <nlohmann/json_fwd.hpp>

#include "core/model.h"

namespace shatter {

nlohmann::ordered_json model_summary(const Model& model);
// The same as an aligned text report.
std::string model_summary_text(const nlohmann::ordered_json& summary);

}  // namespace shatter
