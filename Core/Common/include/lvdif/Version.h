#pragma once

namespace lvdif
{
/// The version of the LVDIFCore library loaded in this process (the project's version).
const char* libraryVersion();
} // namespace lvdif
