#include "pipeline/batch_file.h"

#include <filesystem>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "core/error.h"
#include "core/toml_reader.h"

namespace shatter {

namespace fs = std::filesystem;

std::string BatchFile::cache_dir() const { return (fs::path(output_dir) / ".cache").string(); }

namespace {

constexpr Limits kWorkersLimits{1, 256, "parallel runs"};
constexpr Limits kStripTimeLimits{0, 1e6, "s"};

// A value as it would be written in a shot file (strings quoted, arrays bracketed).
std::string toml_text(const toml::node& n) {
    std::ostringstream out;
    n.visit([&](const auto& v) { out << v; });
    return out.str();
}

// A value as a folder name: "0.5", "12mm", "1-2-0" (no quotes, brackets, separators).
std::string label_text(const toml::node& n) {
    std::string s;
    if (n.is_string()) {
        s = n.as_string()->get();
    } else {
        s = toml_text(n);
    }
    std::string out;
    for (char c : s) {
        if (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '+') out += c;
        else if (c == ',' && !out.empty() && out.back() != '-') out += '-';
    }
    return out.empty() ? "x" : out;
}

// Flattens {render = {width = 640}} and {"render.width" = 640} alike into ("render.width", node).
void flatten(const toml::table& t, const std::string& prefix, std::vector<std::pair<std::string, const toml::node*>>& out) {
    for (auto&& [k, v] : t) {
        const std::string key = prefix.empty() ? std::string(k.str()) : prefix + "." + std::string(k.str());
        if (v.is_table()) flatten(*v.as_table(), key, out);
        else out.emplace_back(key, &v);
    }
}

const toml::table* table_key(TomlSection& s, const char* key) {
    const toml::node* n = s.node(key);
    if (!n) return nullptr;
    if (!n->is_table())
        s.fail(n, fmt::format("{} must be a table of SECTION.KEY = VALUE", s.key_name(key)),
               fmt::format("write e.g. {} = {{ \"material.alpha\" = {} }}", key, key == std::string("sweep") ? "[0, 1]" : "0.5"));
    return n->as_table();
}

BatchJob read_job(TomlSection& s, const BatchFile& batch, const std::vector<std::string>& overrides) {
    BatchJob job;
    if (!s.text("shot", job.shot) || job.shot.empty())
        s.fail(nullptr, fmt::format("{} is missing", s.key_name("shot")), "add shot = \"SHOT.toml\" (relative to the batch file)");
    if (fs::path(job.shot).is_relative())
        job.shot = (fs::path(batch.path).parent_path() / job.shot).lexically_normal().string();
    job.name = fs::path(job.shot).stem().string();
    if (s.text("name", job.name) && (job.name.empty() || job.name.find('/') != std::string::npos || job.name[0] == '.'))
        s.fail(s.node("name"), fmt::format("job name \"{}\" cannot name a folder", job.name),
               "use letters, digits, '-' and '_'");
    double strip = 0;
    if (s.number("strip_time", strip, kStripTimeLimits)) job.strip_time = strip;

    std::vector<std::string> common;
    if (const toml::table* set = table_key(s, "set")) {
        std::vector<std::pair<std::string, const toml::node*>> values;
        flatten(*set, "", values);
        for (const auto& [key, node] : values) common.push_back(key + "=" + toml_text(*node));
    }
    common.insert(common.end(), overrides.begin(), overrides.end());
    // The sweep: the cartesian product, the first key varying slowest.
    struct Axis {
        std::string key, short_name;
        std::vector<const toml::node*> values;
    };
    std::vector<Axis> axes;
    if (const toml::table* sweep = table_key(s, "sweep")) {
        std::vector<std::pair<std::string, const toml::node*>> values;
        flatten(*sweep, "", values);
        for (const auto& [key, node] : values) {
            const toml::array* a = node->as_array();
            if (!a || a->empty())
                s.fail(node, fmt::format("sweep key {} must be a non-empty array of values", key),
                       fmt::format("write e.g. \"{}\" = [0, 0.5, 1]", key));
            Axis axis{key, key.substr(key.rfind('.') + 1), {}};
            for (const toml::node& v : *a) axis.values.push_back(&v);
            axes.push_back(std::move(axis));
            job.sweep_keys.push_back(key);
        }
    }
    size_t combinations = 1;
    for (const Axis& a : axes) combinations *= a.values.size();
    for (size_t i = 0; i < combinations; ++i) {
        BatchRun run;
        run.overrides = common;
        size_t rest = i, stride = combinations;
        for (const Axis& a : axes) {
            stride /= a.values.size();
            const toml::node& v = *a.values[rest / stride];
            rest %= stride;
            run.overrides.push_back(a.key + "=" + toml_text(v));
            run.label += (run.label.empty() ? "" : "_") + a.short_name + "-" + label_text(v);
            run.caption += (run.caption.empty() ? "" : ", ") + a.short_name + " = " + (v.is_string() ? v.as_string()->get() : toml_text(v));
        }
        if (run.label.empty()) run.label = "run", run.caption = job.name;
        run.output_dir = (fs::path(batch.output_dir) / job.name / run.label).string();
        job.runs.push_back(std::move(run));
    }
    job.output_dir = (fs::path(batch.output_dir) / job.name).string();
    s.finish();
    return job;
}

}  // namespace

BatchFile load_batch(const std::string& path, const std::string& output_dir, const std::vector<std::string>& overrides) {
    toml::table root = parse_toml_file(path);
    BatchFile batch;
    batch.path = path;
    batch.overrides = overrides;
    TomlSection top(root, path, "");
    batch.output_dir = (fs::path("out") / fs::path(path).stem()).string();
    if (const toml::node* n = top.node("batch")) {
        if (!n->is_table()) top.fail(n, "'batch' must be a table: [batch]", "see docs/pipeline.md");
        TomlSection s(*n->as_table(), path, "batch");
        s.integer("workers", batch.workers, kWorkersLimits);
        std::string out;
        if (s.text("output", out) && !out.empty()) batch.output_dir = out;
        s.finish();
    }
    if (!output_dir.empty()) batch.output_dir = output_dir;
    const toml::node* jobs = top.node("job");
    if (!jobs || !jobs->is_array_of_tables() || jobs->as_array()->empty())
        top.fail(jobs, "a batch file needs at least one [[job]]", "add [[job]] with shot = \"SHOT.toml\" (docs/pipeline.md)");
    std::set<std::string> names;
    size_t index = 0;
    for (const toml::node& j : *jobs->as_array()) {
        TomlSection s(*j.as_table(), path, fmt::format("job[{}]", index++));
        BatchJob job = read_job(s, batch, overrides);
        if (!names.insert(job.name).second)
            s.fail(nullptr, fmt::format("two jobs are named \"{}\"", job.name), "give each job its own name = \"...\"");
        batch.jobs.push_back(std::move(job));
    }
    top.finish();
    return batch;
}

BatchFile batch_of_files(const std::vector<std::string>& files, const std::string& output_dir,
                         const std::vector<std::string>& overrides) {
    BatchFile batch;
    batch.overrides = overrides;
    batch.output_dir = output_dir.empty() ? (fs::path("out") / "batch").string() : output_dir;
    std::set<std::string> names;
    for (const std::string& file : files)
        if (is_batch_file(file))
            throw Error(ExitCode::Usage, fmt::format("{} is a batch file, given with other files (fix: give one batch "
                                                     "file, or shots and meshes)", file));
    for (const std::string& file : files) {
        std::error_code ec;
        if (!fs::is_regular_file(file, ec))
            throw_input_error(file, fs::exists(file, ec) ? "not a regular file" : "no such file",
                              "give shot files (.toml) or mesh files that exist");
        BatchJob job;
        job.shot = file;
        const fs::path path(file);
        std::string name = path.stem().string();
        if (name.empty() || name[0] == '.') name = "mesh" + name;
        if (names.count(name)) {
            std::string ext = path.extension().string();
            if (!ext.empty()) name += "-" + ext.substr(1);
        }
        const std::string base = name;
        for (int n = 2; names.count(name); ++n) name = base + "-" + std::to_string(n);
        names.insert(name);
        job.name = name;
        job.output_dir = (fs::path(batch.output_dir) / job.name).string();
        BatchRun run;
        run.label = "run";
        run.caption = job.name;
        run.overrides = overrides;
        run.output_dir = (fs::path(job.output_dir) / run.label).string();
        job.runs.push_back(std::move(run));
        batch.jobs.push_back(std::move(job));
    }
    return batch;
}

bool is_batch_file(const std::string& path) {
    if (fs::path(path).extension() != ".toml") return false;  // not read as TOML: a mesh may be large
    try {
        const toml::table root = parse_toml_file(path);
        return root.contains("job") || root.contains("batch");
    } catch (const Error&) {
        return false;
    }
}

}  // namespace shatter
