// MainWindow: the recovery file (autosave, the offer to recover after a
// crash) and the questions before closing a modified volume.
#include "MainWindow.h"

#include <QCloseEvent>
#include <QDir>
#include <QFile>
#include <QMessageBox>
#include <QStandardPaths>
#include <QStatusBar>

#include <exception>

QString MainWindow::recoveryPath() const
{
  QString dir = this->Options.recoveryDir;
  if (dir.isEmpty())
    dir = QStandardPaths::writableLocation(QStandardPaths::AppDataLocation);
  QDir().mkpath(dir);
  return QDir(dir).filePath("recovery.lvdv");
}

void MainWindow::autosave()
{
  if (!this->Doc.hasVolume() || !this->Doc.needsAutosave() || this->Painting)
    return;
  try
  {
    this->Doc.save(this->recoveryPath(), true);
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
  const QString path = this->recoveryPath();
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
  if (answer != QMessageBox::Yes)
    return false;
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
  if (!this->Options.batch() && !this->maybeSave())
  {
    event->ignore();
    return;
  }
  QFile::remove(this->recoveryPath()); // a normal end: nothing to recover
  event->accept();
}
