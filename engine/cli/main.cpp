// rift: command-line entry point. See engine/cli/commands.cpp for the subcommands.
int main() { return 0; }
