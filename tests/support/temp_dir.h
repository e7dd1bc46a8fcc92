// A fresh temporary directory per test, removed at the end.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>

#include <filesystem>
#include <fstream>
#include <string>

namespace shatter::testing_support {

class TempDir {
public:
    TempDir() {
        static int counter = 0;
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        path_ = std::filesystem::temp_directory_path() /
                ("shatter-test-" + sanitize(info->test_suite_name()) + "-" + sanitize(info->name()) + "-" +
                 std::to_string(::getpid()) + "-" + std::to_string(counter++));
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~TempDir() { std::filesystem::remove_all(path_); }
    std::string file(const std::string& name) const { return (path_ / name).string(); }
    std::string write(const std::string& name, const std::string& text) const {
        std::ofstream(file(name), std::ios::binary) << text;
        return file(name);
    }
    const std::filesystem::path& path() const { return path_; }
    // Names of the files in the directory, sorted.
    std::vector<std::string> entries() const {
        std::vector<std::string> out;
        for (auto& e : std::filesystem::directory_iterator(path_)) out.push_back(e.path().filename().string());
        std::sort(out.begin(), out.end());
        return out;
    }

private:
    static std::string sanitize(std::string s) {
        for (char& c : s)
            if (c == '/') c = '_';
        return s;
    }
    std::filesystem::path path_;
};

}  // namespace shatter::testing_support
