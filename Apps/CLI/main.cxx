// lvdif: the command-line tool. `lvdif help` lists the commands.
#include "Commands.h"

#include "lvdif/Error.h"

#include <cstdio>
#include <cstring>
#include <exception>

namespace
{
struct Command
{
  const char* name;
  int (*run)(int, char**);
  const char* help;
};

const Command commands[] = {
  { "demo", CommandDemo, "demo [--out DIR] [--size N]   build, save, mesh and render the bundled example" },
  { "info", CommandInfo, "info VOLUME.lvdv   describe a volume file (header, chunks, colours, metadata)" },
  { "mesh", CommandMesh, "mesh VOLUME OUT.(ply|obj|stl|vtp) [--png OUT.png]   extract the surface of a volume" },
  { "convert", CommandConvert, "convert IN OUT   between .lvdv and the original's .bv" },
  { "mesh-to-sdf", CommandMeshToSdf,
    "mesh-to-sdf MESH OUT.(lvdv|bv) [--dims N] [--padding P] [--sign normal|pseudo|winding] [--reorient] [--svf] [--band B] "
    "[--device cpu|cuda|auto]   voxelize a mesh (OBJ, OFF, STL, PLY)" },
  { "script", CommandScript,
    "script FILE.lvs [--in VOLUME] [--out VOLUME] [--mesh OUT] [--png OUT.png] [--size N]   run a script" },
  { "play", CommandPlay, "play RECORDING.lvr --in VOLUME [--out VOLUME] [--mesh OUT] [--png OUT.png]   replay edits" },
};

int usage(FILE* f)
{
  std::fprintf(f, "usage: lvdif COMMAND [ARGS]\n\ncommands:\n");
  for (const auto& c : commands) std::fprintf(f, "  %s\n", c.help);
  return f == stdout ? 0 : 2;
}
}

int main(int argc, char** argv)
{
  if (argc < 2) return usage(stderr);
  if (!std::strcmp(argv[1], "help") || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h")) return usage(stdout);
  for (const auto& c : commands)
  {
    if (std::strcmp(argv[1], c.name) == 0)
    {
      // `lvdif COMMAND --help` anywhere on the line: that command's usage, nothing run
      for (int i = 2; i < argc; ++i)
      {
        if (!std::strcmp(argv[i], "--help") || !std::strcmp(argv[i], "-h"))
        {
          std::printf("usage: lvdif %s\n", c.help);
          return 0;
        }
      }
      try
      {
        return c.run(argc, argv);
      }
      catch (const lvdif::Error& e)
      {
        std::fprintf(stderr, "lvdif %s: %s\n", c.name, e.what());
        return e.code() == lvdif::ErrorCode::Cancelled ? 130 : 1;
      }
      catch (const std::exception& e)
      {
        std::fprintf(stderr, "lvdif %s: %s\n", c.name, e.what());
        return 1;
      }
    }
  }
  std::fprintf(stderr, "lvdif: unknown command '%s'\n", argv[1]);
  return usage(stderr);
}
