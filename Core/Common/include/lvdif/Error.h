// Error reporting for the VTK-free core: every failure is an lvdif::Error
// carrying a category and a one-line, human-readable message.
#pragma once

#include <stdexcept>
#include <string>

namespace lvdif
{

enum class ErrorCode
{
  InvalidArgument,   // a parameter out of its documented range
  OutOfMemory,       // refused before allocating: the estimate exceeds the limit
  DictionaryFull,    // the colour dictionary has no free key
  CorruptData,       // a file or stream failed validation
  IoFailure,         // the operating system refused a read or write
  ParseError,        // a script or text format could not be parsed
  Cancelled,         // the interrupter asked to stop
  DeviceFailure,     // a CUDA call failed
  Unsupported        // a feature not built in (e.g. CUDA)
};

const char* toString(ErrorCode code);

class Error : public std::runtime_error
{
public:
  Error(ErrorCode code, const std::string& message)
    : std::runtime_error(message)
    , Code(code)
  {
  }
  ErrorCode code() const { return this->Code; }

private:
  ErrorCode Code;
};

/// Throws Error(InvalidArgument, message) when the condition is false.
inline void require(bool condition, const std::string& message)
{
  if (!condition)
  {
    throw Error(ErrorCode::InvalidArgument, message);
  }
}

} // namespace lvdif
