// What the edit fuzz targets do with a recording they read: play it onto a small volume
// under small budgets, so that the shared edit rules, the budgets and the brush run too.
// A refusal (lvdif::Error) is an answer; anything else escapes to libFuzzer as a finding.
#pragma once

#include "lvdif/Editor.h"
#include "lvdif/Recording.h"

inline void playOnSmallVolume(const lvdif::Recording& recording)
{
  try
  {
    lvdif::VolumeOptions o;
    o.dims = { 24, 24, 24 };
    o.chunkEdge = 8;
    lvdif::DictionaryVolume v(o);
    lvdif::Editor e(v);
    e.limits.maxDabsPerEdit = 2000;
    e.limits.maxTotalDabs = 4000;
    e.play(recording);
  }
  catch (const lvdif::Error&)
  {
  }
}
