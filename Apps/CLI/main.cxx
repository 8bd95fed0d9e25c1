// lvdif: the command-line tool. `lvdif help` lists the commands.
#include "Commands.h"

#include "LVDIFVolumeBridge.h"
#include "lvdif/Error.h"

#include "vtkLogger.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <exception>
#include <unistd.h>

namespace
{
/// VTK's messages in the CLI: a failure reaches the user as the one line of
/// the lvdif::Error it becomes (LVDIFFiles watches every algorithm it runs),
/// so VTK's own error text, which objects nobody watches print in VTK's log
/// format through vtkLogger (e.g. the XML parser under a .vti reader: a
/// second error line), is dropped; warnings come as one "warning: ..." line.
class CliOutputWindow : public vtkOutputWindow
{
public:
  static CliOutputWindow* New();
  vtkTypeMacro(CliOutputWindow, vtkOutputWindow);
  void DisplayText(const char* text) override { std::fprintf(stderr, "%s", text ? text : ""); }
  void DisplayErrorText(const char* text) override
  {
    // kept for an abort (VTK aborts on a lost X display right after its error)
    std::snprintf(LastError, sizeof(LastError), "%s", LVDIFVolumeBridge::MessageText(text).c_str());
  }
  static char LastError[1024];
  void DisplayWarningText(const char* text) override
  {
    std::fprintf(stderr, "warning: %s\n", LVDIFVolumeBridge::MessageText(text).c_str());
  }
  void DisplayGenericWarningText(const char* text) override { this->DisplayWarningText(text); }
  void DisplayDebugText(const char*) override {}
};
vtkStandardNewMacro(CliOutputWindow);
char CliOutputWindow::LastError[1024] = "";

extern "C" void onAbort(int sig)
{
  const char* head = "lvdif: aborted: ";
  if (CliOutputWindow::LastError[0] != '\0' && ::write(STDERR_FILENO, head, std::strlen(head)) >= 0 &&
    ::write(STDERR_FILENO, CliOutputWindow::LastError, std::strlen(CliOutputWindow::LastError)) >= 0)
    (void)!::write(STDERR_FILENO, "\n", 1);
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

bool accepted = false; // CommandLineAccepted() was called

struct Command
{
  const char* name;
  int (*run)(int, char**);
  const char* help;
};

const Command commands[] = {
  { "demo", CommandDemo, "demo [--out DIR (default out)] [--size N (default 128)]   build, save, mesh and render the bundled example" },
  { "info", CommandInfo,
    "info VOLUME.lvdv [--header-only]   describe a volume file (header, chunks, colours, metadata) after checking "
    "every chunk; --header-only skips the chunks" },
  { "mesh", CommandMesh, "mesh VOLUME OUT.(ply|obj|stl|vtp) [--png OUT.png]   extract the surface of a volume" },
  { "convert", CommandConvert, "convert IN OUT (each .lvdv, .lvdvp, .bv, .vti or .vdb)   between volume formats (.bv: the original's)" },
  { "mesh-to-sdf", CommandMeshToSdf,
    "mesh-to-sdf MESH OUT.(lvdv|lvdvp|bv|vti|vdb) [--dims N] [--padding P] [--sign normal|pseudo|winding] [--reorient] [--svf] [--band B] "
    "[--device cpu|cuda|auto]   voxelize a mesh (OBJ, OFF, STL, PLY); defaults: --dims 128 voxels on the longest axis (2 to 1048576, as memory allows) "
    "(.bv: on every axis, the original's cubic grid around the mesh), "
    "--padding 2 voxels, --sign winding, --band 8 voxels (0: no band), --device auto" },
  { "script", CommandScript,
    "script FILE.lvs [--in VOLUME] [--out VOLUME] [--mesh OUT.(ply|obj|stl|vtp)] [--png OUT.png] [--size N|NXxNYxNZ] [--max-steps N]   run a "
    "script; --size: the empty start canvas (N^3 or NXxNYxNZ voxels, default 128) of a script without --in and without its own 'canvas'; "
    "--max-steps: the most statements, loop iterations and dabs it may run (default 50000000)" },
  { "play", CommandPlay,
    "play RECORDING.lvr [--in VOLUME | --fill empty|full|sphere] [--out VOLUME] [--mesh OUT.(ply|obj|stl|vtp)] [--png OUT.png]   "
    "replay edits on --in, or without it on the canvas the recording was made on (its 'canvas' line), new as "
    "lvdif-editor makes it: --fill as the editor's, default sphere (the editor's starter shape, the one the recording's "
    "version says)" },
};

const char* const ExitStatusHelp = "exit status: 0 done, 1 failed while running, 2 command line refused (nothing "
                                   "read or written), 130 cancelled (Ctrl-C)";

/// The exit status once stdout is flushed: what a command printed there (info's description, the
/// summary lines, --help) that could not be written is a failure (`lvdif info v.lvdv > /dev/full`
/// exited 0 with nothing written).
int flushed(int status, const char* name)
{
  if (std::fflush(stdout) == 0 && !std::ferror(stdout)) return status;
  const int e = errno;
  std::fprintf(stderr, "lvdif%s%s: cannot write the standard output: %s\n", name ? " " : "", name ? name : "",
    e ? std::strerror(e) : "write error");
  return status == 0 ? 1 : status;
}

int usage(FILE* f)
{
  std::fprintf(f, "usage: lvdif COMMAND [ARGS]\n\ncommands:\n");
  for (const auto& c : commands) std::fprintf(f, "  %s\n", c.help);
  std::fprintf(f, "\n%s\n", ExitStatusHelp);
  return f == stdout ? 0 : 2;
}
}

std::string CommandUsage(const char* name)
{
  for (const auto& c : commands)
    if (!std::strcmp(c.name, name))
    {
      const std::string help = c.help;
      return "usage: lvdif " + help.substr(0, help.find("   ")); // the synopsis, before its description
    }
  return "usage: lvdif " + std::string(name);
}

void CommandLineAccepted()
{
  accepted = true;
}

int main(int argc, char** argv)
{
  if (argc < 2) return usage(stderr);
  vtkNew<CliOutputWindow> messages;
  vtkOutputWindow::SetInstance(messages);
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF); // VTK logs each message there too
  std::signal(SIGABRT, onAbort);
  if (!std::strcmp(argv[1], "help") || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h"))
    return flushed(usage(stdout), nullptr);
  for (const auto& c : commands)
  {
    if (std::strcmp(argv[1], c.name) == 0)
    {
      // `lvdif COMMAND --help` anywhere on the line: that command's usage, nothing run
      for (int i = 2; i < argc; ++i)
      {
        if (!std::strcmp(argv[i], "--help") || !std::strcmp(argv[i], "-h"))
        {
          std::printf("usage: lvdif %s\n\n%s\n", c.help, ExitStatusHelp);
          return flushed(0, c.name);
        }
      }
      try
      {
        return flushed(c.run(argc, argv), c.name);
      }
      catch (const lvdif::Error& e)
      {
        std::fprintf(stderr, "lvdif %s: %s\n", c.name, e.what());
        // 2 for a command line refused before the work, as the editor's (every refusal exited 1)
        return e.code() == lvdif::ErrorCode::Cancelled ? 130 : accepted ? 1 : 2;
      }
      catch (const std::exception& e)
      {
        std::fprintf(stderr, "lvdif %s: %s\n", c.name, e.what());
        return 1; // (std::bad_alloc and the like: never a refused command line)
      }
    }
  }
  std::fprintf(stderr, "lvdif: unknown command '%s'\n", argv[1]);
  return usage(stderr);
}
