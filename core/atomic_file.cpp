#include "core/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"

namespace shatter {

namespace {

std::string errno_text() { return std::strerror(errno); }

}  // namespace

void write_file_atomic(const std::string& path, std::string_view bytes) {
    const std::string tmp = path + ".tmp." + std::to_string(::getpid());
    int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) throw_io_error(path, errno_text());
    size_t done = 0;
    while (done < bytes.size()) {
        ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0) {
            if (errno == EINTR) continue;
            std::string why = errno_text();
            ::close(fd);
            ::unlink(tmp.c_str());
            throw_io_error(path, why);
        }
        done += static_cast<size_t>(n);
    }
    if (::fsync(fd) != 0 || ::close(fd) != 0) {
        std::string why = errno_text();
        ::unlink(tmp.c_str());
        throw_io_error(path, why);
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        std::string why = errno_text();
        ::unlink(tmp.c_str());
        throw_io_error(path, why);
    }
}

std::string read_file(const std::string& path, const char* what) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec))
        throw_input_error(path, std::string(what) + " not found", "check the path");
    if (std::filesystem::is_directory(path, ec))
        throw_input_error(path, std::string(what) + " is a directory", "name a file");
    // A FIFO, socket or device: opening a FIFO with no writer would wait forever.
    if (!std::filesystem::is_regular_file(path, ec))
        throw_input_error(path, std::string(what) + " is not a regular file (a FIFO, socket or device)",
                          "save it to a file and name that");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw_input_error(path, std::string("cannot open ") + what + ": " + errno_text(), "check its permissions");
    std::ostringstream ss;
    ss << in.rdbuf();
    if (in.bad()) throw_input_error(path, std::string("cannot read ") + what, "check the file and the disk");
    return ss.str();
}

void make_directories(const std::string& path) {
    if (path.empty()) return;
    std::error_code ec;
    std::filesystem::create_directories(path, ec);
    if (ec) throw_io_error(path, ec.message());
}

}  // namespace shatter
