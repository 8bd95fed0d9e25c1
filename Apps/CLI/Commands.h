// The CLI's sub-commands; each returns the process exit code and reports
// failures by throwing lvdif::Error (main prints one line and exits with 2
// before CommandLineAccepted(), 1 after it, 130 when cancelled).
#pragma once

#include <string>

/// Each command calls this once it has checked its whole command line (its
/// options, its arguments and the places its outputs go) and before it reads
/// an input or does any work: an error thrown before it is a refused command
/// line (exit status 2), one thrown after it a failure while running (1).
void CommandLineAccepted();
/// "usage: lvdif NAME ..." for a refused command line: the synopsis of NAME's line in
/// `lvdif help` (the commands' own usage lines were copies of it, and drifted from it).
std::string CommandUsage(const char* name);

int CommandDemo(int argc, char** argv);
int CommandInfo(int argc, char** argv);
int CommandMesh(int argc, char** argv);
int CommandConvert(int argc, char** argv);
int CommandMeshToSdf(int argc, char** argv);
int CommandScript(int argc, char** argv);
int CommandPlay(int argc, char** argv);
