// The setting flags of a stage command, made from the setting tables (core/setting_table.h):
// `--set SECTION.KEY=VALUE` for the sections the command reads, and each setting's aliases
// (--alpha, --pieces, --no-adapt, ...) with their --help from the same declaration.
#pragma once

#include <deque>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/setting_table.h"

namespace shatter {

class SettingFlags {
public:
    // Declares --set and the aliases of `sections` on `command` (`name` is the command, for messages).
    SettingFlags(CLI::App& command, std::string name, std::vector<std::string> sections);

    // The --set overrides, after checking that each names a section this command reads.
    const std::vector<std::string>& overrides() const;
    // True when a flag of `section` (an alias or --set) was given.
    bool given(const std::string& section) const;
    // The first flag of `section` given, for messages ("--pieces", "--set prescore.seed=2").
    std::string first_given(const std::string& section) const;
    // Applies the aliases that were given to `shot`, in the tables' order; errors name the flag.
    void apply(Shot& shot) const;

private:
    struct Alias {
        const SettingsSection* section;
        const Setting* setting;
        const FlagAlias* alias;
        std::string value;
        bool given = false;
    };
    std::string command_;
    std::vector<std::string> sections_;
    std::vector<std::string> sets_;
    std::deque<Alias> aliases_;  // stable addresses: CLI11 writes into them
};

}  // namespace shatter
