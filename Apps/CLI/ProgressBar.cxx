#include "ProgressBar.h"

#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <unistd.h>

namespace
{
std::atomic<bool> interrupted{ false };
extern "C" void onInterrupt(int)
{
  interrupted.store(true);
}
}

ProgressBar::ProgressBar()
  : Tty(isatty(STDERR_FILENO) != 0)
{
  std::signal(SIGINT, onInterrupt);
}

ProgressBar::~ProgressBar()
{
  std::signal(SIGINT, SIG_DFL);
  // a stage that failed or was cancelled never says "done": end its bar's
  // line so that the error message starts on a line of its own
  if (this->Tty && this->LastPercent >= 0 && this->LastPercent < 100) std::fputc('\n', stderr);
}

void ProgressBar::start(const char* name)
{
  // a stage that the next one follows ran through (mesh to SDF, then the sign
  // voxel filters, in one call): it is done
  if (this->LastPercent >= 0 && this->LastPercent < 100) this->show(100);
  this->Stage = name ? name : "";
  this->LastPercent = -1;
  this->show(0);
}

void ProgressBar::progress(double fraction)
{
  // 100 % ("done") only through end(): a stage whose work all ran can still
  // fail (a script's open stroke said "script: done", then its error)
  this->show(std::min(static_cast<int>(fraction * 100.0 + 0.5), 99));
}

void ProgressBar::show(int percent)
{
  if (percent == this->LastPercent || (!this->Tty && percent != 100 && percent != 0))
  {
    return;
  }
  this->LastPercent = percent;
  if (this->Tty)
  {
    const int width = 30, filled = percent * width / 100;
    std::fprintf(stderr, "\r%-16s [%.*s%*s] %3d%%", this->Stage.c_str(), filled,
      "##############################", width - filled, "", percent);
    if (percent >= 100) std::fputc('\n', stderr);
  }
  else if (percent >= 100)
  {
    std::fprintf(stderr, "%s: done\n", this->Stage.c_str());
  }
  std::fflush(stderr);
}

bool ProgressBar::wasInterrupted() const
{
  return interrupted.load();
}

void ProgressBar::end()
{
  if (this->LastPercent < 100) this->show(100);
}
