// MainWindow: the recovery file (autosave, the offer to recover after a
// crash) and the questions before closing a modified volume.
#include "MainWindow.h"

#include <QCloseEvent>
#include <QCoreApplication>
#include <QDir>
#include <QFile>
#include <QLockFile>
#include <QMessageBox>
#include <QStandardPaths>
#include <QStatusBar>

#include <cstdio>
#include <exception>
#include <memory>

void MainWindow::claimRecoverySlot(const QString& skip)
{
  QString dir = this->Options.recoveryDir;
  if (dir.isEmpty())
    dir = QStandardPaths::writableLocation(QStandardPaths::AppDataLocation);
  QDir().mkpath(dir);
  // The first slot holding an autosave that no running editor owns (a
  // session that did not end normally: offered), else the first free slot
  // (only free slots with --no-recovery, which offers nothing).
  // A lock whose process is gone is stale and taken over (QLockFile); age
  // alone never makes one stale (staleLockTime 0): editors run for days.
  constexpr int Slots = 16;
  std::unique_ptr<QLockFile> free;
  QString freeFile;
  for (int i = 0; i < Slots; ++i)
  {
    const QString file = QDir(dir).filePath(i == 0 ? QString("recovery.lvdv") : QString("recovery-%1.lvdv").arg(i + 1));
    if (file == skip)
      continue;
    auto lock = std::make_unique<QLockFile>(file + ".lock");
    lock->setStaleLockTime(0);
    if (!lock->tryLock(0))
      continue; // a running editor's
    if (QFile::exists(file))
    {
      if (this->Options.noRecovery)
        continue; // not offered: not overwritten either
      this->RecoveryFile = file;
      this->RecoveryLock = std::move(lock);
      return; // `free` unlocks as it goes
    }
    if (!free)
    {
      free = std::move(lock);
      freeFile = file;
    }
  }
  if (free)
  {
    this->RecoveryFile = freeFile;
    this->RecoveryLock = std::move(free);
    return;
  }
  // every slot in use: a file of this process's own, unguarded
  this->RecoveryFile =
    QDir(dir).filePath(QString("recovery-pid%1.lvdv").arg(QCoreApplication::applicationPid()));
}

QString MainWindow::recoveryPath()
{
  if (this->RecoveryFile.isEmpty())
    this->claimRecoverySlot();
  return this->RecoveryFile;
}

void MainWindow::autosave()
{
  if (!this->Doc.hasVolume() || !this->Doc.needsAutosave() || this->Painting)
    return;
  try
  {
    this->Doc.save(this->recoveryPath(), true);
    this->RecoveryOwned = true;
    this->Doc.autosaved();
    this->statusBar()->showMessage("Autosaved to " + this->recoveryPath(), 3000);
  }
  catch (const std::exception& e)
  {
    this->statusBar()->showMessage(QString("Autosave failed: ") + e.what(), 5000);
  }
}

bool MainWindow::offerRecovery()
{
  const QString path = this->recoveryPath(); // claims this editor's slot, also with --no-recovery
  if (this->Options.noRecovery || !QFile::exists(path))
    return false;
  const QString& given = this->Options.recoveryAnswer; // tests
  const auto answer = !given.isEmpty()
    ? (given == "yes" ? QMessageBox::Yes : (given == "discard" ? QMessageBox::Discard : QMessageBox::No))
    : QMessageBox::question(this, "Recover",
        "An autosaved volume from a session that did not end normally exists:\n" + path + "\n\nRecover it?",
        QMessageBox::Yes | QMessageBox::No | QMessageBox::Discard);
  if (answer == QMessageBox::Discard)
    QFile::remove(path);
  if (answer == QMessageBox::No)
  {
    // kept for a later session: this one autosaves elsewhere
    this->RecoveryLock.reset();
    this->RecoveryFile.clear();
    this->claimRecoverySlot(path);
  }
  if (answer != QMessageBox::Yes)
    return false;
  this->RecoveryOwned = true;
  // untitled and modified: Save asks where to put it. Opened as the recovery
  // file's document, Save wrote into recovery.lvdv and the next normal exit
  // deleted that file with the work saved in it.
  return this->openVolume(path, true);
}

bool MainWindow::maybeSave()
{
  if (!this->Doc.hasVolume() || !this->Doc.modified())
    return true;
  const auto answer = QMessageBox::warning(this, "Unsaved changes", "The volume has been modified. Save it?",
    QMessageBox::Save | QMessageBox::Discard | QMessageBox::Cancel);
  if (answer == QMessageBox::Cancel)
    return false;
  if (answer == QMessageBox::Save)
    return this->Doc.path().isEmpty() ? this->saveAsDialog() : this->saveVolume(this->Doc.path());
  return true;
}

void MainWindow::closeEvent(QCloseEvent* event)
{
  // a recording in progress is saved as Stop saves it (the window closed and
  // it was gone); Cancel keeps the window open
  if (!this->Options.batch() && (!this->maybeSave() || !this->finishRecording()))
  {
    event->ignore();
    return;
  }
  // a batch run has nobody to answer the recording's Save dialog: said, not silent
  if (this->Options.batch() && this->Doc.hasVolume() && this->Doc.session().recording())
    std::fprintf(stderr, "lvdif-editor: warning: the recording in progress was not saved (Ctrl+R stops and saves it)\n");
  if (this->RecoveryOwned)
    QFile::remove(this->RecoveryFile); // a normal end: nothing to recover
  event->accept();
}
