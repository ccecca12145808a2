// The whole `vaegail` command tree, so that main() and the quickstart (which runs the same
// commands a user would type) build it the same way.
#pragma once

#include <CLI/CLI.hpp>

#include <memory>
#include <string>

namespace vaegail::cli {

std::unique_ptr<CLI::App> make_app();

// Parses one command line (without the program name) on a fresh app and runs it; echoes it
// first as "$ vaegail ...". Errors propagate as exceptions.
void run_command_line(const std::string& line);

}  // namespace vaegail::cli
