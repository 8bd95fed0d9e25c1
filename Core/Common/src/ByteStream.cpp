#include "lvdif/ByteStream.h"

#include "lvdif/Error.h"

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <dirent.h>
#include <vector>
#include <cstring>
#include <fcntl.h>
#include <string>
#include <sys/stat.h>
#include <unistd.h>

namespace lvdif
{

namespace
{
std::string systemError(const std::string& what, const std::string& path)
{
  return what + " '" + path + "': " + std::strerror(errno);
}

std::string directoryOf(const std::string& path);

/// The nearest existing path above `path` when it is not a folder (a file
/// where a folder of the path should be), else "".
std::string fileAbove(const std::string& path)
{
  struct stat st;
  std::string up = directoryOf(path);
  while (::stat(up.c_str(), &st) != 0 && up != "." && up != "/")
  {
    up = directoryOf(up);
  }
  return ::stat(up.c_str(), &st) == 0 && !S_ISDIR(st.st_mode) ? up : std::string();
}

void checkRange(std::uint64_t offset, std::size_t n, std::uint64_t size)
{
  if (offset > size || n > size - offset)
  {
    throw Error(ErrorCode::CorruptData,
      "read of " + std::to_string(n) + " bytes at offset " + std::to_string(offset) + " passes the end of the " +
        std::to_string(size) + "-byte input (truncated file)");
  }
}

class FdSink : public ByteSink
{
public:
  FdSink(int fd, const std::string& path)
    : Fd(fd)
    , Path(path)
  {
  }
  void write(const void* data, std::size_t n) override
  {
    const char* p = static_cast<const char*>(data);
    std::size_t left = n;
    while (left > 0)
    {
      const ssize_t w = ::write(this->Fd, p, left);
      if (w < 0)
      {
        if (errno == EINTR)
        {
          continue;
        }
        throw Error(ErrorCode::IoFailure, systemError("cannot write", this->Path));
      }
      p += w;
      left -= static_cast<std::size_t>(w);
    }
    this->Written += n;
  }

private:
  int Fd;
  std::string Path;
};

std::string directoryOf(const std::string& path)
{
  const auto slash = path.find_last_of('/');
  if (slash == std::string::npos)
  {
    return ".";
  }
  return slash == 0 ? "/" : path.substr(0, slash);
}

// A symlink is saved through: the file written is the link's final target
// (also when that does not exist yet), so the link stays a link.
std::string resolveLinks(const std::string& path)
{
  std::string p = path;
  for (int hops = 0; hops < 40; ++hops)
  {
    struct stat st;
    if (::lstat(p.c_str(), &st) != 0 || !S_ISLNK(st.st_mode))
      return p;
    std::vector<char> buf(static_cast<std::size_t>(st.st_size > 0 ? st.st_size : 255) + 1);
    const ssize_t n = ::readlink(p.c_str(), buf.data(), buf.size());
    if (n < 0 || static_cast<std::size_t>(n) >= buf.size())
      throw Error(ErrorCode::IoFailure, systemError("cannot read the link", p));
    const std::string target(buf.data(), static_cast<std::size_t>(n));
    p = !target.empty() && target[0] == '/' ? target : directoryOf(p) + "/" + target;
  }
  throw Error(ErrorCode::IoFailure, "cannot save '" + path + "': too many levels of symbolic links");
}

// Temporary files are "<name>.tmp-<pid>-XXXXXX"; one whose process is gone
// is the leftover of a killed save and is removed by the next save.
std::string tempPrefix(const std::string& path)
{
  return path + ".tmp-";
}

void removeStaleTemps(const std::string& path)
{
  const std::string dir = directoryOf(path);
  const std::string base = tempPrefix(path).substr(path.find_last_of('/') == std::string::npos ? 0 : path.find_last_of('/') + 1);
  DIR* d = ::opendir(dir.c_str());
  if (!d)
    return;
  while (const dirent* e = ::readdir(d))
  {
    const std::string name = e->d_name;
    if (name.compare(0, base.size(), base) != 0)
      continue;
    char* end = nullptr;
    const long pid = std::strtol(name.c_str() + base.size(), &end, 10);
    if (pid <= 0 || *end != '-' || std::strlen(end) < 7 || (std::strlen(end) > 7 && end[7] != '.'))
      continue;
    if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH)
      continue; // its save may still be running
    ::unlink((dir + "/" + name).c_str());
  }
  ::closedir(d);
}
} // namespace

void removeStaleTemporaries(const std::string& path)
{
  removeStaleTemps(path);
}

void MemorySource::read(std::uint64_t offset, void* dst, std::size_t n)
{
  checkRange(offset, n, this->Size);
  if (n)
  {
    std::memcpy(dst, this->Data + offset, n);
  }
#pragma omp atomic
  this->BytesRead += n;
}

FileSource::FileSource(const std::string& path)
  : Path(path)
{
  // O_NONBLOCK: opening a FIFO must not wait for a writer; it is refused below
  this->Fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (this->Fd < 0)
  {
    // FILE/x.obj said "Not a directory"
    const std::string file = errno == ENOTDIR ? fileAbove(path) : std::string();
    throw Error(ErrorCode::IoFailure,
      file.empty() ? systemError("cannot open", path) : "cannot open '" + path + "': '" + file + "' is a file, not a folder");
  }
  struct stat st;
  const bool known = ::fstat(this->Fd, &st) == 0;
  if (!known || !S_ISREG(st.st_mode))
  {
    const bool folder = known && S_ISDIR(st.st_mode); // said: "not a regular file" left the user guessing
    ::close(this->Fd);
    this->Fd = -1;
    throw Error(ErrorCode::IoFailure, "'" + path + (folder ? "' is a folder, not a regular file" : "' is not a regular file"));
  }
  ::fcntl(this->Fd, F_SETFL, ::fcntl(this->Fd, F_GETFL) & ~O_NONBLOCK);
  this->Size = static_cast<std::uint64_t>(st.st_size);
}

FileSource::~FileSource()
{
  if (this->Fd >= 0)
  {
    ::close(this->Fd);
  }
}

void FileSource::read(std::uint64_t offset, void* dst, std::size_t n)
{
  checkRange(offset, n, this->Size);
  char* p = static_cast<char*>(dst);
  std::size_t left = n;
  std::uint64_t at = offset;
  while (left > 0)
  {
    const ssize_t r = ::pread(this->Fd, p, left, static_cast<off_t>(at));
    if (r < 0 && errno == EINTR)
    {
      continue;
    }
    if (r < 0)
    {
      throw Error(ErrorCode::IoFailure, systemError("cannot read", this->Path));
    }
    if (r == 0)
    {
      throw Error(ErrorCode::CorruptData, "'" + this->Path + "' became shorter while being read");
    }
    p += r;
    at += static_cast<std::uint64_t>(r);
    left -= static_cast<std::size_t>(r);
  }
#pragma omp atomic
  this->BytesRead += n;
}

void MemorySink::write(const void* data, std::size_t n)
{
  const auto* p = static_cast<const std::uint8_t*>(data);
  this->Buffer.insert(this->Buffer.end(), p, p + n);
  this->Written += n;
}

namespace
{
struct Target
{
  std::string path; // after symlinks
  bool exists = false;
  struct stat old;
};

Target prepareSave(const std::string& givenPath)
{
  // the front ends' own early check, so that every save (vtkLVDIFEditor, the
  // writers) names a missing folder as the CLI does, not the temporary file
  requireWritable(givenPath);
  Target t;
  t.path = resolveLinks(givenPath);
  t.exists = ::stat(t.path.c_str(), &t.old) == 0;
  removeStaleTemps(t.path);
  return t;
}

// mkstemp creates 0600: an existing file keeps its mode (and owner, where
// allowed); a new one is an ordinary document
void applyMode(int fd, const Target& t)
{
  if (t.exists)
  {
    ::fchmod(fd, t.old.st_mode & 07777);
    if (::fchown(fd, t.old.st_uid, t.old.st_gid) != 0)
    {
      // not permitted for other users' files: the file becomes ours, as any rewrite would
    }
  }
  else
  {
    ::fchmod(fd, 0644);
  }
}

// keepExtension: "<name>.tmp-<pid>-XXXXXX.<ext>", for writers that insist on
// their extension (VTK's PLY writer appends ".ply" to any other name)
int makeTemp(const Target& t, std::string& tmp, bool keepExtension = false)
{
  std::string suffix;
  const std::size_t slash = t.path.find_last_of('/'), dot = t.path.find_last_of('.');
  if (keepExtension && dot != std::string::npos && (slash == std::string::npos || dot > slash))
    suffix = t.path.substr(dot);
  tmp = tempPrefix(t.path) + std::to_string(::getpid()) + "-XXXXXX" + suffix;
  std::vector<char> name(tmp.begin(), tmp.end());
  name.push_back('\0');
  const int fd = ::mkostemps(name.data(), static_cast<int>(suffix.size()), O_CLOEXEC);
  if (fd < 0)
  {
    throw Error(ErrorCode::IoFailure, systemError("cannot create a temporary file beside", t.path));
  }
  tmp.assign(name.data());
  return fd;
}

void commit(const std::string& tmp, const std::string& path)
{
  if (::rename(tmp.c_str(), path.c_str()) != 0)
  {
    const std::string msg = systemError("cannot rename the temporary file over", path);
    ::unlink(tmp.c_str());
    throw Error(ErrorCode::IoFailure, msg);
  }
  // make the rename itself durable
  const int dir = ::open(directoryOf(path).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir >= 0)
  {
    ::fsync(dir);
    ::close(dir);
  }
}
} // namespace

void saveAtomically(const std::string& givenPath, const std::function<void(ByteSink&)>& produce)
{
  const Target t = prepareSave(givenPath);
  std::string tmp;
  const int fd = makeTemp(t, tmp);
  bool open = true;
  try
  {
    applyMode(fd, t);
    FdSink sink(fd, tmp);
    produce(sink);
    if (::fsync(fd) != 0)
    {
      throw Error(ErrorCode::IoFailure, systemError("cannot flush", tmp));
    }
    open = false;
    if (::close(fd) != 0)
    {
      throw Error(ErrorCode::IoFailure, systemError("cannot close", tmp));
    }
  }
  catch (...)
  {
    if (open)
    {
      ::close(fd);
    }
    ::unlink(tmp.c_str());
    throw;
  }
  commit(tmp, t.path);
}

void saveAtomicallyByName(const std::string& givenPath, const std::function<void(const std::string&)>& produce)
{
  const Target t = prepareSave(givenPath);
  std::string tmp;
  int fd = makeTemp(t, tmp, true);
  ::close(fd);
  try
  {
    produce(tmp);
    fd = ::open(tmp.c_str(), O_RDWR | O_CLOEXEC);
    struct stat st;
    if (fd < 0 || ::fstat(fd, &st) != 0 || st.st_size == 0)
    {
      throw Error(ErrorCode::IoFailure, "could not write '" + givenPath + "' (the writer produced nothing)");
    }
    applyMode(fd, t);
    if (::fsync(fd) != 0)
    {
      throw Error(ErrorCode::IoFailure, systemError("cannot flush", tmp));
    }
    const int rc = ::close(fd);
    fd = -1;
    if (rc != 0)
    {
      throw Error(ErrorCode::IoFailure, systemError("cannot close", tmp));
    }
  }
  catch (...)
  {
    if (fd >= 0)
    {
      ::close(fd);
    }
    ::unlink(tmp.c_str());
    throw;
  }
  commit(tmp, t.path);
}

void requireWritable(const std::string& givenPath)
{
  if (givenPath.empty())
  {
    throw Error(ErrorCode::InvalidArgument, "empty output file name");
  }
  const std::string path = resolveLinks(givenPath);
  struct stat st;
  if (::stat(path.c_str(), &st) == 0)
  {
    if (!S_ISREG(st.st_mode))
    {
      throw Error(ErrorCode::IoFailure,
        "cannot write '" + givenPath + (S_ISDIR(st.st_mode) ? "': a folder, not a regular file" : "': not a regular file"));
    }
    if (::access(path.c_str(), W_OK) != 0)
    {
      throw Error(ErrorCode::IoFailure, systemError("cannot write", givenPath));
    }
  }
  const std::string dir = directoryOf(path);
  if (::stat(dir.c_str(), &st) != 0 || !S_ISDIR(st.st_mode))
  {
    // a file where a folder should be is named as the cause (FILE/x.lvdv said
    // "the folder 'FILE' does not exist")
    const std::string file = fileAbove(path);
    if (!file.empty())
    {
      throw Error(ErrorCode::IoFailure, "cannot write '" + givenPath + "': '" + file + "' is a file, not a folder");
    }
    throw Error(ErrorCode::IoFailure, "cannot write '" + givenPath + "': the folder '" + dir + "' does not exist");
  }
  const std::string notWritable = "cannot write '" + givenPath + "': the folder '" + dir + "' is not writable";
  if (::access(dir.c_str(), W_OK | X_OK) != 0)
  {
    throw Error(ErrorCode::IoFailure, notWritable);
  }
  // access() reads the mode bits only (root passes them everywhere): a folder
  // that takes no new files (/proc, a read-only mount) is found by creating the
  // temporary file a save creates there, and removing it at once (the save
  // itself said "cannot create a temporary file beside ...: No such file or directory")
  std::string probe = tempPrefix(path) + std::to_string(::getpid()) + "-XXXXXX";
  std::vector<char> name(probe.begin(), probe.end());
  name.push_back('\0');
  const int fd = ::mkostemp(name.data(), O_CLOEXEC);
  if (fd < 0)
  {
    if (errno == ENOSPC || errno == EDQUOT || errno == EMFILE || errno == ENFILE || errno == ENAMETOOLONG)
    {
      throw Error(ErrorCode::IoFailure, systemError("cannot write", givenPath));
    }
    throw Error(ErrorCode::IoFailure, notWritable);
  }
  ::close(fd);
  ::unlink(name.data());
}

} // namespace lvdif
