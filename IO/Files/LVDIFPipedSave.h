// The safe save of a VTK writer that does not check its own writes.
#ifndef LVDIFPipedSave_h
#define LVDIFPipedSave_h

#include <functional>
#include <string>

namespace LVDIFFiles
{
/// The safe save (lvdif::saveAtomically) of a VTK writer that says nothing when
/// a write fails (vtkPLYWriter and vtkOBJWriter write through an unchecked FILE*
/// or ofstream, so on a full disk Write() answered 1 over a cut file, which the
/// save then renamed over the old one). The writer writes into a pipe (through a
/// link to its /proc/self/fd path: it writes in order, never seeks) and a thread
/// copies the bytes into the save's checked sink, whose failure (ENOSPC) is the
/// save's. False, nothing written, where no link can be made beside the file (a
/// FAT folder): the caller saves by name.
bool SaveThroughPipe(const std::string& path, const std::function<void(const std::string& target)>& write);
}

#endif
