#include "cmd/setting_flags.h"

#include <algorithm>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "cmd/command.h"
#include "core/error.h"

namespace shatter {

namespace {

std::string unquoted(const std::string& text) {
    return text.size() >= 2 && text.front() == '"' && text.back() == '"' ? text.substr(1, text.size() - 2) : text;
}

std::string alias_help(const SettingsSection& section, const Setting& s, const FlagAlias& a) {
    const std::string key = section.name + "." + s.key;
    switch (a.kind) {
        case FlagKind::SetsTrue: return fmt::format("{} (--set {}=true; default: off)", s.help, key);
        case FlagKind::SetsFalse: return fmt::format("--set {}=false; {}: {} (default: {})", key, s.key, s.help,
                                                     unquoted(s.default_text));
        case FlagKind::Value: break;
    }
    return option_help(s.help, s.unit, unquoted(s.default_text)) + fmt::format(" [{}]", key);
}

std::string section_of(const std::string& override_text) { return override_text.substr(0, override_text.find('.')); }

}  // namespace

SettingFlags::SettingFlags(CLI::App& command, std::string name, std::vector<std::string> sections)
    : command_(std::move(name)), sections_(std::move(sections)) {
    std::vector<std::string> listed;
    for (const std::string& s : sections_) listed.push_back("[" + s + "]");
    command.add_option("--set", sets_,
                       fmt::format("set a shot setting of {}, SECTION.KEY=VALUE, written as in the shot file "
                                   "(repeatable; docs/shot.md), e.g. --set {}; applied after the shot file, before the flags below",
                                   fmt::join(listed, ", "),
                                   sections_.front() == "mesh" ? "prescore.pieces=6"
                                   : sections_.front() == "render" ? "render.fov=30" : "material.alpha=2"))
        ->allow_extra_args(false)
        ->type_name("SECTION.KEY=VALUE");
    for (const std::string& section_name : sections_) {
        const SettingsSection* section = find_settings_section(section_name);
        for (const Setting& setting : section->settings)
            for (const FlagAlias& alias : setting.flags) {
                Alias& a = aliases_.emplace_back(Alias{section, &setting, &alias, "", false});
                const std::string help = alias_help(*section, setting, alias);
                if (alias.kind == FlagKind::Value)
                    command
                        .add_option_function<std::string>(
                            alias.name, [&a](const std::string& v) { a.value = v, a.given = true; }, help)
                        ->type_name("VALUE");
                else
                    command.add_flag_function(alias.name, [&a](int64_t) { a.given = true; }, help);
            }
    }
}

const std::vector<std::string>& SettingFlags::overrides() const {
    for (const std::string& o : sets_)
        if (std::find(sections_.begin(), sections_.end(), section_of(o)) == sections_.end()) {
            std::vector<std::string> listed;
            for (const std::string& s : sections_) listed.push_back("[" + s + "]");
            throw Error(ExitCode::Usage,
                        fmt::format("--set {}: shatter {} does not read [{}] (fix: set a key of {} here; shatter run "
                                    "--set takes every section)", o, command_, section_of(o), fmt::join(listed, ", ")));
        }
    return sets_;
}

bool SettingFlags::given(const std::string& section) const { return !first_given(section).empty(); }

std::string SettingFlags::first_given(const std::string& section) const {
    for (const Alias& a : aliases_)
        if (a.given && a.section->name == section) return a.alias->name;
    for (const std::string& o : sets_)
        if (section_of(o) == section) return "--set " + o;
    return "";
}

void SettingFlags::apply(Shot& shot) const {
    const Setting* previous = nullptr;
    const Alias* previous_alias = nullptr;
    for (const Alias& a : aliases_) {
        if (!a.given) continue;
        if (previous == a.setting)  // two aliases of one setting (--hollow and --solid)
            throw Error(ExitCode::Usage, fmt::format("{}: {} also sets {}.{} (fix: give one of them)",
                                                     a.alias->name, previous_alias->alias->name, a.section->name,
                                                     a.setting->key));
        apply_flag(*a.section, *a.setting, *a.alias, a.value, shot);
        previous = a.setting;
        previous_alias = &a;
    }
}

}  // namespace shatter
