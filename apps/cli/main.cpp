// breastfit: registers a rigged template torso to a 3D breast scan and transfers surgical drawings.
#include "commands.h"
#include "run_app.h"

int main(int argc, char** argv) { return breastfit::cli::run_app(argc, argv, breastfit::cli::kCommands); }
