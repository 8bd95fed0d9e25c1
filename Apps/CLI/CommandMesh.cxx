// `lvdif mesh VOLUME OUT`: extract the surface of a saved volume.
#include "Arguments.h"
#include "Commands.h"

#include "lvdif/Error.h"

int CommandMesh(int argc, char** argv)
{
  Arguments args(argc, argv, 2);
  args.allowOnly({ "png" });
  throw lvdif::Error(lvdif::ErrorCode::Unsupported, "reading volume files is not built yet");
}
