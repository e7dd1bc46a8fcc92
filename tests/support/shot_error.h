// The message of the BadInput error that loading a shot file raises (a test failure when none).
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "core/error.h"
#include "core/shot.h"

namespace shatter::testing_support {

inline std::string shot_load_error(const std::string& path) {
    try {
        load_shot(path);
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::BadInput);
        return e.what();
    }
    ADD_FAILURE() << "no error for " << path;
    return "";
}

}  // namespace shatter::testing_support
