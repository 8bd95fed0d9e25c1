// MainWindow: recording strokes, playing recordings back and running scripts.
#include "MainWindow.h"

#include "lvdif/Error.h"
#include "lvdif/Recording.h"
#include "lvdif/Script.h"

#include "LVDIFFiles.h"
#include "VolumeFiles.h" // the CLI's rule of an output on the volume's dimensions

#include <cstdio>

#include <QFileDialog>
#include <QFileInfo>
#include <QMessageBox>
#include <QStatusBar>

#include <cstdio>

void MainWindow::toggleRecording(bool on)
{
  if (!this->Doc.hasVolume())
  {
    this->Tools->setRecording(false);
    return;
  }
  if (on)
  {
    this->Doc.startRecording();
    this->Tools->setRecording(true);
    return;
  }
  this->stopAndSaveRecording();
}

bool MainWindow::stopAndSaveRecording()
{
  // a volume that replaced the recorded one (a script's `canvas N`) ended the
  // recording: Stop threw "not recording" out of the button's slot and the
  // editor aborted, with the unsaved volume
  if (!this->Doc.session().recording())
  {
    this->Tools->setRecording(false);
    return true;
  }
  // The file first, then the stop: Cancel in the dialog cancels the stop, and
  // the recording goes on (Stop asks again). It stopped first and Cancel then
  // threw the recorded work away.
  QString path = QFileDialog::getSaveFileName(this, "Save recording", QString(), "Recordings (*.lvr)");
  if (path.isEmpty())
  {
    this->Tools->setRecording(true);
    this->statusBar()->showMessage("The recording goes on: not saved (Stop asks again)", 5000);
    return false;
  }
  if (QFileInfo(path).suffix().isEmpty())
    path += ".lvr"; // as Save as adds .lvdv
  try
  {
    // a folder that is not there or not writable: said while the recording
    // can still go on (it cannot be resumed once stopped)
    LVDIFFiles::RequireWritable(path.toStdString());
  }
  catch (const std::exception& e)
  {
    this->Tools->setRecording(true);
    this->showError("Cannot save the recording (it goes on: Stop asks again)", e);
    return false;
  }
  const lvdif::Recording r = this->Doc.stopRecording();
  this->Tools->setRecording(false);
  try
  {
    lvdif::saveRecording(path.toStdString(), r);
  }
  catch (const std::exception& e)
  {
    this->showError("Cannot save the recording", e);
  }
  return true;
}

bool MainWindow::playRecording(const QString& path)
{
  if (!this->Doc.hasVolume())
    return false;
  try
  {
    const lvdif::Recording recording = lvdif::loadRecording(path.toStdString());
    const int before = this->Doc.generation();
    this->Doc.play(recording);
    if (this->Doc.generation() != before)
      this->volumeReplaced(); // an old recording's own starter canvas
    if (!recording.warning.empty())
    {
      // a version 1 recording (no end record): played, said once
      if (this->Options.batch())
        std::fprintf(stderr, "lvdif-editor: warning: %s\n", recording.warning.c_str());
      else
        QMessageBox::warning(this, "Play recording", QString::fromStdString(recording.warning));
    }
  }
  catch (const std::exception& e)
  {
    this->updateTitle(); // the records played before the error are kept: '*'
    this->showError("Cannot play " + path, e);
    return false;
  }
  this->updateTitle();
  return true;
}

namespace
{
bool hasRecordingExtension(const QString& path)
{
  const QString suffix = QFileInfo(path).suffix().toLower();
  return suffix == "lvr" || suffix == "lvrec";
}
} // namespace

bool isRecordingText(const std::string& source)
{
  std::size_t at = 0;
  while (at < source.size())
  {
    const std::size_t end = std::min(source.find('\n', at), source.size());
    const std::size_t first = source.find_first_not_of(" \t\r", at);
    if (first < end && source[first] != '#')
      return source.compare(first, 15, "LVDIF-RECORDING") == 0;
    at = end + 1;
  }
  return false;
}

bool isScriptFile(const QString& path)
{
  if (hasRecordingExtension(path))
    return false;
  try
  {
    return !isRecordingText(lvdif::readScriptFile(path.toLocal8Bit().toStdString()));
  }
  catch (const std::exception&)
  {
    return true; // runScript reports why it cannot be read
  }
}

bool MainWindow::runScript(const QString& path)
{
  if (hasRecordingExtension(path))
    return this->playRecording(path);
  std::string source;
  try
  {
    source = lvdif::readScriptFile(path.toLocal8Bit().toStdString()); // the one script reader (no FIFO, no folder)
  }
  catch (const std::exception& e)
  {
    this->showError("Cannot read " + path, e);
    return false;
  }
  // A recording by its first line, whatever its name: one saved without the
  // extension (the Save recording dialog adds none) was run as a script and
  // failed with "unknown command 'LVDIF'".
  if (isRecordingText(source))
    return this->playRecording(path);
  const int before = this->Doc.hasVolume() ? this->Doc.generation() : -1;
  lvdif::ScriptOptions options;
  // A batch run's --save: its rule on the volume's grid (a .bv is cubic, a .vdb
  // has one spacing), checked before the script runs, and at a `canvas N` before
  // it makes the canvas, as `lvdif script --out` does (the whole script ran, then
  // the save failed).
  if (this->Options.batch() && !this->Options.save.isEmpty())
    options.resultRule = [save = this->Options.save.toStdString()](
                           const lvdif::Index3& dims, const std::array<double, 3>& spacing) {
      return VolumeOutputDimsProblem(save, dims, spacing.data());
    };
  // While recording, a script that can make a new canvas (a `canvas N`, taken
  // branch or not) stops the recording first and asks for its file, as New and
  // Open do: the new volume ended the recording without a word, and the
  // recorded strokes were lost. Core refuses such a script before any of it
  // runs when the start canvas is fixed by its caller (canvasSizeGivenBy): the
  // recording's canvas is. Cancel in the dialog: the script does not run, the
  // recording goes on.
  static const std::string byRecording = "by the recording in progress";
  const bool recording = this->Doc.hasVolume() && this->Doc.session().recording();
  if (recording)
    options.canvasSizeGivenBy = byRecording;
  try
  {
    if (!this->Doc.hasVolume())
      this->Doc.newCanvas(128, 128, 128, VolumeDocument::Fill::Empty);
    try
    {
      this->Doc.runScript(source, options);
    }
    catch (const lvdif::ScriptError& e)
    {
      if (!recording || e.detail().find(byRecording) == std::string::npos)
        throw;
      // nothing ran
      const QString why = "The script " + QFileInfo(path).fileName() +
        " makes a new canvas: the recording of this volume stops first (Save recording)";
      if (this->Options.batch())
        std::fprintf(stderr, "lvdif-editor: warning: %s\n", why.toLocal8Bit().constData());
      this->statusBar()->showMessage(why);
      if (!this->finishRecording())
        return false; // Cancel: the recording goes on, the script did not run
      options.canvasSizeGivenBy.clear();
      this->Doc.runScript(source, options);
    }
  }
  catch (const std::exception& e)
  {
    // a `canvas N` before the error replaced the volume all the same: show it
    if (this->Doc.hasVolume() && this->Doc.generation() != before)
      this->volumeReplaced();
    this->updateTitle();
    this->showError("The script " + QFileInfo(path).fileName() + " failed", e);
    return false;
  }
  if (this->Doc.generation() != before)
    this->volumeReplaced();
  this->updateTitle();
  return true;
}

bool MainWindow::finishRecording()
{
  // A new volume is a new edit session: the recording of the old one ended
  // with it, unsaved, and the Stop button then aborted the editor. Stopped
  // first, it is saved as Stop saves it; Cancel there keeps the recording and
  // the volume, and the caller does not replace it.
  if (this->Doc.hasVolume() && this->Doc.session().recording())
    return this->stopAndSaveRecording();
  return true;
}
