#pragma once
/// \file Each subcommand lives in <name>_command.cpp and registers itself on the app.
/// A command's callback does the work, throws breastfit::InvalidInput / IoError on bad input,
/// and may set `exit_code` (see exit_codes.h) for outcomes that are not exceptions.
#include <CLI/CLI.hpp>

namespace breastfit::cli {

using RegisterFn = void (*)(CLI::App& app, int& exit_code);

void register_inspect(CLI::App& app, int& exit_code);
void register_template(CLI::App& app, int& exit_code);
void register_render(CLI::App& app, int& exit_code);
void register_register(CLI::App& app, int& exit_code);
void register_synth(CLI::App& app, int& exit_code);
void register_bench(CLI::App& app, int& exit_code);
void register_demo(CLI::App& app, int& exit_code);
void register_map(CLI::App& app, int& exit_code);
void register_experiments(CLI::App& app, int& exit_code);
void register_volume(CLI::App& app, int& exit_code);
void register_batch(CLI::App& app, int& exit_code);
/// The workstation's command, in breastfit-serve (serve_main.cpp).
void register_serve(CLI::App& app, int& exit_code);
/// `breastfit serve`: runs breastfit-serve with its arguments (serve_launcher.cpp).
void register_serve_launcher(CLI::App& app, int& exit_code);
void register_landmarks(CLI::App& app, int& exit_code);

inline constexpr RegisterFn kCommands[] = {
    register_inspect, register_template, register_render, register_register,
    register_synth,   register_bench,    register_demo,    register_map,
    register_experiments, register_volume, register_batch, register_serve_launcher, register_landmarks,
};

}  // namespace breastfit::cli
