// The CLI's sub-commands; each returns the process exit code and reports
// failures by throwing lvdif::Error (main prints one line and exits 1).
#pragma once

int CommandDemo(int argc, char** argv);
int CommandInfo(int argc, char** argv);
int CommandMesh(int argc, char** argv);
int CommandConvert(int argc, char** argv);
int CommandMeshToSdf(int argc, char** argv);
int CommandScript(int argc, char** argv);
int CommandPlay(int argc, char** argv);
