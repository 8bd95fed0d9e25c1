// The loopback TCP input device: one client at a time, one JSON object per
// line (see lvdif/InputDevice.h). Non-blocking sockets polled by the editor.
#include "lvdif/InputDevice.h"

#include "lvdif/Error.h"

#include <arpa/inet.h>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

namespace lvdif
{

namespace
{
void setNonBlocking(int fd)
{
  const int flags = ::fcntl(fd, F_GETFL, 0);
  ::fcntl(fd, F_SETFL, flags | O_NONBLOCK);
}
} // namespace

SocketDevice::SocketDevice(int port)
{
  require(port >= 0 && port <= 65535, "socket device port must be in [0, 65535]");
  this->ListenFd = ::socket(AF_INET, SOCK_STREAM, 0);
  if (this->ListenFd < 0)
  {
    throw Error(ErrorCode::IoFailure, std::string("cannot create a socket: ") + std::strerror(errno));
  }
  const int one = 1;
  ::setsockopt(this->ListenFd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof(one));
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK); // loopback only: never exposed to the network
  addr.sin_port = htons(static_cast<std::uint16_t>(port));
  if (::bind(this->ListenFd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) != 0 ||
    ::listen(this->ListenFd, 1) != 0)
  {
    const std::string why = std::strerror(errno);
    ::close(this->ListenFd);
    throw Error(ErrorCode::IoFailure, "cannot listen on 127.0.0.1:" + std::to_string(port) + ": " + why);
  }
  socklen_t len = sizeof(addr);
  ::getsockname(this->ListenFd, reinterpret_cast<sockaddr*>(&addr), &len);
  this->Port = ntohs(addr.sin_port);
  setNonBlocking(this->ListenFd);
}

SocketDevice::~SocketDevice()
{
  this->close();
}

void SocketDevice::close()
{
  if (this->ClientFd >= 0)
    ::close(this->ClientFd);
  if (this->ListenFd >= 0)
    ::close(this->ListenFd);
  this->ClientFd = this->ListenFd = -1;
  this->Closed = true;
}

void SocketDevice::consumeLines()
{
  std::size_t start = 0;
  for (;;)
  {
    const std::size_t nl = this->Buffer.find('\n', start);
    if (nl == std::string::npos)
      break;
    if (this->Discarding)
    {
      this->Discarding = false; // the tail of an over-long line (already counted once)
    }
    else
    {
      std::string line = this->Buffer.substr(start, nl - start);
      if (!line.empty() && line.back() == '\r')
        line.pop_back();
      if (line.find_first_not_of(" \t") != std::string::npos)
      {
        BrushSample s;
        std::string why;
        if (parseSampleJson(line, s, &why))
        {
          this->Queue.push_back(s);
        }
        else
        {
          ++this->Errors;
          this->LastError = why;
        }
      }
    }
    start = nl + 1;
  }
  this->Buffer.erase(0, start);
  if (this->Discarding)
  {
    this->Buffer.clear(); // still inside the over-long line: drop, no new error
  }
  else if (this->Buffer.size() > MaxLine)
  {
    ++this->Errors;
    this->LastError = "line longer than " + std::to_string(MaxLine) + " bytes dropped";
    this->Buffer.clear();
    this->Discarding = true;
  }
}

void SocketDevice::pump(int timeoutMs)
{
  if (this->Closed)
    return;
  if (this->ClientFd < 0)
  {
    pollfd p{ this->ListenFd, POLLIN, 0 };
    if (::poll(&p, 1, timeoutMs) <= 0)
      return;
    this->ClientFd = ::accept(this->ListenFd, nullptr, nullptr);
    if (this->ClientFd < 0)
      return;
    setNonBlocking(this->ClientFd);
    this->Buffer.clear();
    this->Discarding = false;
  }
  pollfd p{ this->ClientFd, POLLIN, 0 };
  if (::poll(&p, 1, timeoutMs) <= 0)
    return;
  // Bounded work per call: at most MaxBytesPerPump bytes and never past a full
  // queue; what is left waits in the kernel's buffer and then the client's
  // (TCP back-pressure), so a flooding client cannot freeze the caller or
  // grow memory.
  char buf[4096];
  std::size_t read = 0;
  while (read < MaxBytesPerPump && this->Queue.size() < MaxQueue)
  {
    const ssize_t n = ::recv(this->ClientFd, buf, sizeof(buf), 0);
    if (n > 0)
    {
      read += static_cast<std::size_t>(n);
      this->Buffer.append(buf, static_cast<std::size_t>(n));
      this->consumeLines();
      continue;
    }
    if (n < 0 && errno == EINTR)
      continue;
    if (n == 0 || (errno != EAGAIN && errno != EWOULDBLOCK))
    {
      // client gone: a final line without newline still counts
      if (!this->Discarding && !this->Buffer.empty())
      {
        this->Buffer += '\n';
        this->consumeLines();
      }
      this->Discarding = false;
      ::close(this->ClientFd);
      this->ClientFd = -1;
    }
    break;
  }
}

bool SocketDevice::poll(BrushSample& out, int timeoutMs)
{
  if (this->Queue.empty())
  {
    this->pump(timeoutMs);
  }
  if (this->Queue.empty())
  {
    return false;
  }
  out = this->Queue.front();
  this->Queue.pop_front();
  return true;
}

} // namespace lvdif
