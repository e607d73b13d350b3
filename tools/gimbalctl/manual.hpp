// `gimbalctl --help` reads like a man page: NAME, SYNOPSIS, DESCRIPTION, OPTIONS (each with
// its default), COMMANDS, EXAMPLES, EXIT STATUS. The layout is generated from the CLI11
// declarations so the manual cannot drift from what the parser accepts.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace gimbalctl {

// A titled section whose text is word-wrapped to the manual's width.
std::string manual_section(const std::string& title, const std::string& text);

// Installs the manual formatter on `app` (inherited by sub-commands added later) and sets the
// top-level description and the EXAMPLES / EXIT STATUS sections.
void install_manual(CLI::App& app);

}  // namespace gimbalctl
