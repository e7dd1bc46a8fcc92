#include "pipeline/tool_output.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "core/error.h"

namespace shatter {

ToolOutput::ToolOutput(const std::string& target, const std::string& extension) : target_(target) {
    const std::filesystem::path absolute = std::filesystem::absolute(target);
    const std::string name = absolute.filename().string() + ".tmp." + std::to_string(::getpid()) + extension;
    tmp_ = (absolute.parent_path() / name).string();
    const int fd = ::open(tmp_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) throw_io_error(target, std::strerror(errno));
    ::close(fd);
}

ToolOutput::~ToolOutput() {
    if (!committed_) std::remove(tmp_.c_str());
}

void ToolOutput::commit() {
    if (std::rename(tmp_.c_str(), target_.c_str()) != 0) throw_io_error(target_, std::strerror(errno));
    committed_ = true;
}

}  // namespace shatter
