// MainWindow: the file dialogs, mesh export and screenshots.
#include "MainWindow.h"

#include "lvdif/ByteStream.h"
#include "lvdif/Error.h"
#include "vtkPartialRedrawCuller.h"

#include "LVDIFFiles.h"

#include "vtkChunkActorManager.h"
#include "vtkCleanPolyData.h"
#include "vtkGenericOpenGLRenderWindow.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <QComboBox>
#include <QDialog>
#include <QDialogButtonBox>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QImage>
#include <QPainter>
#include <QPixmap>
#include <QMessageBox>
#include <QSpinBox>

#include <cstdio>
#include <stdexcept>

namespace
{
/// A picture saved as the CLI saves one, a temporary file renamed over the old: QImage::save truncated
/// the old picture first, so a save that failed midway (a full disk) destroyed it. "" when saved,
/// else why not.
std::string savePicture(const QImage& image, const QString& path, const char* noImage)
{
  try
  {
    if (image.isNull())
      return noImage;
    lvdif::saveAtomicallyByName(path.toLocal8Bit().toStdString(), [&](const std::string& tmp) {
      if (!image.save(QString::fromLocal8Bit(tmp.c_str()), "PNG"))
        throw lvdif::Error(lvdif::ErrorCode::IoFailure, "the PNG writer failed");
      // QImage::save said yes to a file cut by a full disk or a file size limit (its last buffer is
      // written on close, unchecked): read back, as the CLI's pictures and meshes are
      const QImage back(QString::fromLocal8Bit(tmp.c_str()), "PNG");
      if (back.isNull() || back.size() != image.size())
        throw lvdif::Error(lvdif::ErrorCode::IoFailure, "the file written holds no whole picture (the disk full, or a "
          "file size limit?); the old file is kept");
    });
  }
  catch (const std::exception& e)
  {
    return e.what();
  }
  return "";
}
} // namespace

void MainWindow::newDialog()
{
  if (!this->maybeSave())
    return;
  QDialog dlg(this);
  dlg.setWindowTitle("New canvas");
  auto* form = new QFormLayout(&dlg);
  QSpinBox* sizes[3];
  const char* names[3] = { "X voxels", "Y voxels", "Z voxels" };
  for (int a = 0; a < 3; ++a)
  {
    sizes[a] = new QSpinBox(&dlg);
    // the editors' one canvas rule, as --new, `lvdif script --size` and a script's `canvas N` (the dialog stopped at
    // 4096, where they take 1048576 a side, as memory allows: a larger canvas's memory is refused when made)
    sizes[a]->setRange(static_cast<int>(lvdif::DictionaryVolume::MinCanvasDimension),
      static_cast<int>(lvdif::DictionaryVolume::MaxDimension));
    sizes[a]->setValue(128);
    form->addRow(names[a], sizes[a]);
  }
  auto* fill = new QComboBox(&dlg);
  fill->addItems({ "Sphere", "Empty", "Full" });
  form->addRow("Fill", fill);
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel, &dlg);
  form->addRow(buttons);
  connect(buttons, &QDialogButtonBox::accepted, &dlg, &QDialog::accept);
  connect(buttons, &QDialogButtonBox::rejected, &dlg, &QDialog::reject);
  if (dlg.exec() != QDialog::Accepted)
    return;
  const VolumeDocument::Fill f = fill->currentIndex() == 0
    ? VolumeDocument::Fill::Sphere
    : (fill->currentIndex() == 1 ? VolumeDocument::Fill::Empty : VolumeDocument::Fill::Full);
  this->newCanvas(sizes[0]->value(), sizes[1]->value(), sizes[2]->value(), f);
}

namespace
{
/// The dialog's file types, from the one file registry.
QString dialogFilter(LVDIFFiles::Kind kind, bool forSaving)
{
  return QString::fromStdString(LVDIFFiles::DialogFilter(kind, forSaving)) + ";;All files (*)";
}
}

void MainWindow::openDialog()
{
  if (!this->maybeSave())
    return;
  const QString path = QFileDialog::getOpenFileName(
    this, "Open volume", QString(), dialogFilter(LVDIFFiles::Kind::Volume, false));
  if (!path.isEmpty())
    this->openVolume(path);
}

void MainWindow::openMeshDialog()
{
  if (!this->maybeSave())
    return;
  const QString path = QFileDialog::getOpenFileName(
    this, "Open mesh", QString(), dialogFilter(LVDIFFiles::Kind::Mesh, false));
  if (path.isEmpty() || !askMeshImportSettings(this, this->MeshSettings))
    return;
  this->openMesh(path, this->MeshSettings);
}

bool MainWindow::saveAsDialog()
{
  QString path =
    QFileDialog::getSaveFileName(this, "Save volume", this->Doc.path(), dialogFilter(LVDIFFiles::Kind::Volume, true));
  if (path.isEmpty())
    return false;
  if (QFileInfo(path).suffix().isEmpty())
    path += ".lvdv";
  return this->saveVolume(path);
}

void MainWindow::exportDialog()
{
  const QString path =
    QFileDialog::getSaveFileName(this, "Export mesh", QString(), dialogFilter(LVDIFFiles::Kind::Mesh, true));
  if (!path.isEmpty())
    this->exportMesh(path);
}

bool MainWindow::exportMesh(const QString& path)
{
  bool empty = false;
  try
  {
    this->Doc.waitMeshingIdle(); // every chunk, not only those shown so far
    this->showFinishedMeshes();
    // The chunk meshes repeat their boundary vertices bit-identically: merge them.
    vtkNew<vtkCleanPolyData> clean;
    clean->SetInputData(this->Chunks->GetMergedMesh());
    clean->PointMergingOn();
    clean->SetTolerance(0.0);
    clean->Update();
    vtkPolyData* mesh = clean->GetOutput();
    // A volume without a surface (an Empty or Full canvas) exports an empty
    // mesh, a valid file, with a warning, as `lvdif mesh` does: it was an
    // error (no file, exit status 1) where the CLI writes the file.
    empty = mesh->GetNumberOfPolys() == 0;
    if (!mesh->GetPoints())
      mesh->SetPoints(vtkSmartPointer<vtkPoints>::New()); // VTK's writers refuse a mesh without points
    LVDIFFiles::SaveMesh(mesh, path.toLocal8Bit().constData()); // by extension, the one file registry
  }
  catch (const std::exception& e)
  {
    this->showError("Cannot export " + path, e);
    return false;
  }
  if (empty)
  {
    const QString warning =
      "the volume has no surface (its distances never change sign at 0), so the mesh has no triangles";
    if (this->Options.batch())
      std::fprintf(stderr, "lvdif-editor: warning: %s\n", warning.toLocal8Bit().constData());
    else
      QMessageBox::warning(this, "Export mesh", "Exported " + path + ", but " + warning + ".");
  }
  return true;
}

bool MainWindow::saveWindowShot(const QString& path)
{
  // the whole window (menus, toolbar, tool panel, status bar); Qt composes the
  // OpenGL view's current frame into it, except a native view's (its own
  // window): that frame is drawn over its container's place
  const bool single = this->RenderWindow->GetSingleSampleFrames();
  this->RenderWindow->SetSingleSampleFrames(false); // with the view's multisampling
  this->Redraw->RequestFullRedraw();
  this->RenderWindow->Render();
  QPixmap shot = this->grab();
  if (this->NativeView && !shot.isNull())
  {
    QPainter painter(&shot);
    painter.drawImage(QRect(this->ViewWidget->mapTo(this, QPoint(0, 0)), this->ViewWidget->size()), this->grabView());
  }
  this->RenderWindow->SetSingleSampleFrames(single);
  const std::string failed = savePicture(shot.toImage(), path, "no window image to save");
  if (!failed.empty())
    this->showError("Cannot write " + path, std::runtime_error(failed));
  return failed.empty();
}

bool MainWindow::saveScreenshot(const QString& path)
{
  const bool single = this->RenderWindow->GetSingleSampleFrames();
  this->RenderWindow->SetSingleSampleFrames(false); // with the view's multisampling
  this->Redraw->RequestFullRedraw(); // a picture to keep: drawn whole, not an interactive frame
  this->RenderWindow->Render();
  const QImage image = this->grabView().convertToFormat(QImage::Format_RGB888);
  this->RenderWindow->SetSingleSampleFrames(single);
  const std::string failed = savePicture(image, path, "no frame to save");
  if (!failed.empty())
    this->showError("Cannot write " + path, std::runtime_error(failed));
  return failed.empty();
}

void MainWindow::screenshotDialog()
{
  const QString path = QFileDialog::getSaveFileName(this, "Screenshot", QString(), "PNG (*.png)");
  if (!path.isEmpty())
    this->saveScreenshot(path);
}

void MainWindow::scriptDialog()
{
  const QString path =
    QFileDialog::getOpenFileName(this, "Run script", QString(), "Scripts and recordings (*.lvs *.lvr *.lvrec);;All files (*)");
  if (!path.isEmpty())
    this->runScript(path);
}
