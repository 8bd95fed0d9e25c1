// The abstract input device (paper Sect. 3.4: "cross-device input"; the
// original's AbstractInputDevice, original-code-spec.md section 6.1): anything
// that produces BrushSample values can drive the brush. Three implementations
// live in the core:
//   ReplayDevice  replays a list of samples (e.g. captured earlier);
//   ScriptDevice  asks a generator function for sample i (procedural input);
//   SocketDevice  listens on a loopback TCP port and reads one flat JSON object
//                 per line, so external trackers (VR controllers, hand tracking,
//                 haptic styluses) can drive the brush from any language:
//     {"position":[x,y,z], "orientation":[w,x,y,z], "pressure":0.5,
//      "buttons":1, "time":12.25}
//   ("pos" and "quat" are accepted too; only position is required; unknown keys
//   are ignored; a line that is not such an object is skipped and counted in
//   errorCount()). The Qt app adds mouse and tablet devices.
// Devices are polled from one thread (the editor's loop); poll never blocks
// longer than its timeout.
#pragma once

#include "lvdif/Stroke.h"

#include <cstdint>
#include <deque>
#include <functional>
#include <string>
#include <vector>

namespace lvdif
{

class InputDevice
{
public:
  virtual ~InputDevice() = default;
  virtual std::string name() const = 0;
  /// Writes the next sample and returns true if one is available within timeoutMs.
  virtual bool poll(BrushSample& out, int timeoutMs = 0) = 0;
  /// True once the device will never produce another sample.
  virtual bool finished() const = 0;
};

class ReplayDevice : public InputDevice
{
public:
  explicit ReplayDevice(std::vector<BrushSample> samples);
  std::string name() const override { return "replay"; }
  bool poll(BrushSample& out, int timeoutMs = 0) override;
  bool finished() const override { return this->Next >= this->Samples.size(); }

private:
  std::vector<BrushSample> Samples;
  std::size_t Next = 0;
};

class ScriptDevice : public InputDevice
{
public:
  /// generator(i, sample) fills sample i and returns false when there are no more.
  using Generator = std::function<bool(std::uint64_t index, BrushSample& sample)>;
  explicit ScriptDevice(Generator generator);
  std::string name() const override { return "script"; }
  bool poll(BrushSample& out, int timeoutMs = 0) override;
  bool finished() const override { return this->Done; }

private:
  Generator Gen;
  std::uint64_t Index = 0;
  bool Done = false;
};

/// Parses one line of the socket protocol. Returns false (with a message naming the
/// column) for anything that is not a flat JSON object with a 3-number position.
bool parseSampleJson(const std::string& line, BrushSample& out, std::string* error = nullptr);

class SocketDevice : public InputDevice
{
public:
  /// Listens on 127.0.0.1:port (0 picks a free port). Error(IoFailure) if it cannot.
  explicit SocketDevice(int port = 0);
  ~SocketDevice() override;
  SocketDevice(const SocketDevice&) = delete;
  SocketDevice& operator=(const SocketDevice&) = delete;

  std::string name() const override { return "socket"; }
  int port() const { return this->Port; }
  bool poll(BrushSample& out, int timeoutMs = 0) override;
  bool finished() const override { return this->Closed; }
  void close();

  std::uint64_t errorCount() const { return this->Errors; }
  const std::string& lastError() const { return this->LastError; }
  /// Longest accepted line; a longer one is dropped and counted as one error.
  static constexpr std::size_t MaxLine = 64 * 1024;
  /// Most samples waiting to be polled; reading stops while the queue is full.
  static constexpr std::size_t MaxQueue = 4096;
  /// Most bytes read from the client by one poll (bounds the time per pump).
  static constexpr std::size_t MaxBytesPerPump = 256 * 1024;

private:
  void pump(int timeoutMs);
  void consumeLines();

  int ListenFd = -1;
  int ClientFd = -1;
  int Port = 0;
  bool Closed = false;
  bool Discarding = false; // inside an over-long line
  std::string Buffer;
  std::deque<BrushSample> Queue;
  std::uint64_t Errors = 0;
  std::string LastError;
};

} // namespace lvdif
