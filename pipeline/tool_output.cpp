#include "pipeline/tool_output.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "core/error.h"

namespace shatter {

ToolOutput::ToolOutput(const std::string& target, const std::string& extension) : target_(target) {
    const std::filesystem::path absolute = std::filesystem::absolute(target);
    dir_ = (absolute.parent_path() / (absolute.filename().string() + ".tmp." + std::to_string(::getpid()))).string();
    tmp_ = (std::filesystem::path(dir_) / ("output" + extension)).string();
    if (::mkdir(dir_.c_str(), 0755) != 0 && errno != EEXIST) throw_io_error(target, std::strerror(errno));
    const int fd = ::open(tmp_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) {
        const int saved = errno;
        ::rmdir(dir_.c_str());
        throw_io_error(target, std::strerror(saved));
    }
    ::close(fd);
}

ToolOutput::~ToolOutput() {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
}

void ToolOutput::commit() {
    if (std::rename(tmp_.c_str(), target_.c_str()) != 0) throw_io_error(target_, std::strerror(errno));
    committed_ = true;
    ::rmdir(dir_.c_str());
}

}  // namespace shatter
