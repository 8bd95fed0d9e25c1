#include "LVDIFPipedSave.h"

#include "lvdif/Error.h"
#include "lvdif/ByteStream.h"

#include <cerrno>
#include <exception>
#include <fcntl.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace LVDIFFiles
{
bool SaveThroughPipe(const std::string& path, const std::function<void(const std::string& target)>& write)
{
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0)
    return false;
  // the writer is given a link to the pipe named as the save's temporary files ("x.ply.tmp-PID-XXXXXX.ply":
  // the file's extension, as vtkPLYWriter adds ".ply" to a name without it; a killed save's is
  // removed by the next save, lvdif::removeStaleTemporaries). A folder without links (FAT): false.
  const auto dot = path.find_last_of('.'), slash = path.find_last_of('/');
  const std::string ext = dot == std::string::npos || (slash != std::string::npos && dot < slash) ? "" : path.substr(dot);
  std::string link = path + ".tmp-" + std::to_string(::getpid()) + "-XXXXXX" + ext;
  const int made = ::mkstemps(&link[0], static_cast<int>(ext.size()));
  const bool linked = made >= 0 && ::close(made) == 0 && ::unlink(link.c_str()) == 0 &&
    ::symlink(("/proc/self/fd/" + std::to_string(fds[1])).c_str(), link.c_str()) == 0;
  auto closePipe = [&] {
    ::unlink(link.c_str());
    if (fds[1] >= 0)
      ::close(fds[1]);
    ::close(fds[0]);
  };
  if (!linked)
  {
    if (made >= 0)
      ::unlink(link.c_str()); // (a file or a link left by a failed step)
    closePipe();
    return false;
  }
  try
  {
    lvdif::saveAtomically(path, [&](lvdif::ByteSink& sink) {
      std::exception_ptr failed;
      // drains the pipe to its end even after a failure (a writer left writing into a
      // closed pipe would get SIGPIPE)
      std::thread copy([&] {
        std::vector<char> buffer(std::size_t(1) << 16);
        for (;;)
        {
          const ssize_t n = ::read(fds[0], buffer.data(), buffer.size());
          if (n < 0 && errno == EINTR)
            continue;
          if (n <= 0)
            break;
          if (!failed)
          {
            try
            {
              sink.write(buffer.data(), static_cast<std::size_t>(n));
            }
            catch (...)
            {
              failed = std::current_exception();
            }
          }
        }
      });
      try
      {
        write(link);
      }
      catch (...)
      {
        ::close(fds[1]);
        fds[1] = -1;
        copy.join();
        throw;
      }
      ::close(fds[1]); // the writer closed its own: the copy reads to the end
      fds[1] = -1;
      copy.join();
      if (failed)
        std::rethrow_exception(failed);
    });
  }
  catch (...)
  {
    closePipe();
    throw;
  }
  closePipe();
  return true;
}
}
