// shatter settings-doc FILE... (hidden): rewrites the settings tables of docs/shot.md and
// docs/render.md from the declarations (core/setting_table.h), between their
// "<!-- settings:SECTION -->" markers. tests/core/settings_doc_test.cpp fails when they differ.
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cmd/command.h"
#include "core/atomic_file.h"
#include "core/setting_table.h"

namespace shatter {

RunCommand add_settings_doc_command(CLI::App& root) {
    auto files = std::make_shared<std::vector<std::string>>();
    CLI::App* c = root.add_subcommand("settings-doc", "rewrite the settings tables of docs files from the declarations");
    c->group("");  // hidden: a tool for whoever adds a setting
    c->add_option("files", *files, "Markdown files with <!-- settings:SECTION --> markers")->required();
    return [files] {
        for (const std::string& file : *files) {
            const std::string before = read_file(file, "docs file");
            const std::string after = update_settings_docs(before);
            if (after != before) write_file_atomic(file, after);
            fmt::print("{}: {}\n", file, after == before ? "up to date" : "rewritten");
        }
        return 0;
    };
}

}  // namespace shatter
