#include "lvdif/ByteStream.h"

#include "lvdif/Error.h"

#include <cerrno>
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
  FdSink(int fd, const std::string& path, const SaveHooks& hooks)
    : Fd(fd)
    , Path(path)
    , Hooks(hooks)
  {
  }
  void write(const void* data, std::size_t n) override
  {
    if (this->Hooks.beforeWrite)
    {
      this->Hooks.beforeWrite(this->Written, n);
    }
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
  const SaveHooks& Hooks;
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
} // namespace

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
  this->Fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (this->Fd < 0)
  {
    throw Error(ErrorCode::IoFailure, systemError("cannot open", path));
  }
  struct stat st;
  if (::fstat(this->Fd, &st) != 0 || !S_ISREG(st.st_mode))
  {
    ::close(this->Fd);
    this->Fd = -1;
    throw Error(ErrorCode::IoFailure, "'" + path + "' is not a regular file");
  }
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

void saveAtomically(const std::string& path, const std::function<void(ByteSink&)>& produce, const SaveHooks& hooks)
{
  if (path.empty())
  {
    throw Error(ErrorCode::InvalidArgument, "cannot save: empty file name");
  }
  std::string tmp = path + ".tmp-XXXXXX";
  std::vector<char> name(tmp.begin(), tmp.end());
  name.push_back('\0');
  const int fd = ::mkostemp(name.data(), O_CLOEXEC);
  if (fd < 0)
  {
    throw Error(ErrorCode::IoFailure, systemError("cannot create a temporary file beside", path));
  }
  tmp.assign(name.data());
  bool open = true;
  try
  {
    // mkstemp creates 0600; a saved volume is an ordinary document
    ::fchmod(fd, 0644);
    FdSink sink(fd, tmp, hooks);
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

} // namespace lvdif
