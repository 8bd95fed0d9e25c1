// A terminal progress bar as an lvdif::Interrupter: draws "stage [#####   ] 42%"
// on stderr (one line per stage when stderr is not a terminal) and turns
// Ctrl-C into a cancel request that the core honours at its next check.
#pragma once

#include "lvdif/Interrupter.h"

#include <string>

class ProgressBar : public lvdif::Interrupter
{
public:
  ProgressBar();
  ~ProgressBar() override;
  void start(const char* name) override;
  void progress(double fraction) override;
  bool wasInterrupted() const override;
  void end() override;

private:
  void show(int percent);
  std::string Stage;
  int LastPercent = -1;
  bool Tty = false;
};
