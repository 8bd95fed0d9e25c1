// The one source of LVDIFCore itself; every other object comes from a subsystem.
#include "lvdif/Version.h"

namespace lvdif
{
const char* libraryVersion() { return LVDIF_VERSION_STRING; }
} // namespace lvdif
