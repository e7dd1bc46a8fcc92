#include "core/error.h"

namespace shatter {

void throw_input_error(const std::string& where, const std::string& problem, const std::string& fix) {
    std::string message = where + ": " + problem;
    if (!fix.empty()) message += " (fix: " + fix + ")";
    throw Error(ExitCode::BadInput, message);
}

void throw_io_error(const std::string& path, const std::string& reason) {
    throw Error(ExitCode::Io, "cannot write " + path + ": " + reason +
                                  " (fix: free space or grant write access, or choose another output folder; "
                                  "outputs already finished are kept)");
}

}  // namespace shatter
