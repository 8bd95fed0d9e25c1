#include "lvdif/Error.h"
#include "lvdif/Interrupter.h"

namespace lvdif
{

const char* toString(ErrorCode code)
{
  switch (code)
  {
    case ErrorCode::InvalidArgument: return "invalid argument";
    case ErrorCode::OutOfMemory: return "out of memory";
    case ErrorCode::DictionaryFull: return "dictionary full";
    case ErrorCode::CorruptData: return "corrupt data";
    case ErrorCode::IoFailure: return "I/O failure";
    case ErrorCode::ParseError: return "parse error";
    case ErrorCode::Cancelled: return "cancelled";
    case ErrorCode::DeviceFailure: return "device failure";
    case ErrorCode::Unsupported: return "unsupported";
  }
  return "error";
}

Interrupter& nullInterrupter()
{
  static Interrupter instance;
  return instance;
}

} // namespace lvdif
