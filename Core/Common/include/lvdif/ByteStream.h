// Byte sources and sinks for the file readers and writers, so the same code
// reads a file (pread, only the ranges asked for) or a buffer in memory (tests,
// fuzzers), and writes a file or a buffer. Plus the crash-safe save used by
// every writer: write `target.tmp-XXXXXX` beside the target, fsync, rename
// over the target, fsync the directory (the previous file survives any
// failure before the rename).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace lvdif
{

class ByteSource
{
public:
  virtual ~ByteSource() = default;
  virtual std::uint64_t size() const = 0;
  /// Reads exactly n bytes at offset; throws Error(CorruptData) if the range
  /// passes the end (callers validate first; this is the last line of defence)
  /// and Error(IoFailure) if the system refuses.
  virtual void read(std::uint64_t offset, void* dst, std::size_t n) = 0;
  /// Payload bytes read so far (tests check that partial reads read little).
  std::uint64_t bytesRead() const { return this->BytesRead; }

protected:
  std::uint64_t BytesRead = 0;
};

class MemorySource : public ByteSource
{
public:
  MemorySource(const void* data, std::size_t size)
    : Data(static_cast<const std::uint8_t*>(data))
    , Size(size)
  {
  }
  std::uint64_t size() const override { return this->Size; }
  void read(std::uint64_t offset, void* dst, std::size_t n) override;

private:
  const std::uint8_t* Data;
  std::size_t Size;
};

class FileSource : public ByteSource
{
public:
  /// Opens for reading; throws Error(IoFailure) naming the path.
  explicit FileSource(const std::string& path);
  ~FileSource() override;
  FileSource(const FileSource&) = delete;
  FileSource& operator=(const FileSource&) = delete;
  std::uint64_t size() const override { return this->Size; }
  void read(std::uint64_t offset, void* dst, std::size_t n) override;
  const std::string& path() const { return this->Path; }

private:
  std::string Path;
  int Fd = -1;
  std::uint64_t Size = 0;
};

class ByteSink
{
public:
  virtual ~ByteSink() = default;
  /// Appends n bytes; throws Error(IoFailure) on failure.
  virtual void write(const void* data, std::size_t n) = 0;
  std::uint64_t bytesWritten() const { return this->Written; }

protected:
  std::uint64_t Written = 0;
};

class MemorySink : public ByteSink
{
public:
  void write(const void* data, std::size_t n) override;
  std::vector<std::uint8_t>& buffer() { return this->Buffer; }

private:
  std::vector<std::uint8_t> Buffer;
};

/// Crash-safe save: `produce` writes the whole file into the sink, which is a
/// temporary file beside `path`; on success it is fsync'ed and renamed over
/// `path` and the directory is fsync'ed. On any failure (an exception from
/// `produce`, the hook or the system) the temporary file is removed and the
/// exception propagates; the previous file at `path` is untouched (the tests
/// make `produce` fail at every stage through a sink that throws part way).
/// A symlink at `path` is written through (its target is replaced, the link
/// stays); an existing file keeps its mode; a path that is a directory, FIFO or
/// device is refused; temporary files of saves killed earlier (their process is
/// gone) are removed first. Every file the project saves goes through here.
void saveAtomically(const std::string& path, const std::function<void(ByteSink&)>& produce);

/// The same save for writers that open a file by name (VTK's writers):
/// `produce` writes the whole file at the temporary path it is given; a
/// missing or empty result is a failure (Error IoFailure).
void saveAtomicallyByName(const std::string& path, const std::function<void(const std::string& tmpPath)>& produce);

/// Removes the temporary files of saves of `path` killed earlier
/// ("<path>.tmp-<pid>-XXXXXX[.ext]" whose process is gone), as saveAtomically
/// does first; for writers whose files are saved under several names (the
/// pieces of a .lvdvp set).
void removeStaleTemporaries(const std::string& path);

/// Checks, before any expensive work, that `path` can be saved: its directory
/// exists and is writable, and an existing file (or a symlink's target) is a
/// writable regular file. Error IoFailure naming the problem.
void requireWritable(const std::string& path);

} // namespace lvdif
