#include "MeshImport.h"

#include "vtkLVDIFMeshReader.h"
#include "LVDIFVolumeBridge.h"
#include "vtkMeshToSDF.h"
#include "vtkSparseDictionaryVolume.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataSet.h"
#include "vtkExecutive.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"

#include "lvdif/MeshToSdf.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDialog>
#include <QDialogButtonBox>
#include <QEventLoop>
#include <QFormLayout>
#include <QProgressDialog>
#include <QSpinBox>
#include <QTimer>

#include <atomic>
#include <mutex>
#include <thread>

namespace
{
/// Collects the first vtkErrorMacro (or vtkWarningMacro) message from the worker thread instead of printing it.
struct ErrorCollector : vtkCommand
{
  static ErrorCollector* New() { return new ErrorCollector; }
  void Execute(vtkObject*, unsigned long, void* data) override
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    if (this->Text.empty() && data)
      this->Text = LVDIFVolumeBridge::MessageText(static_cast<const char*>(data));
  }
  std::string text()
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    return this->Text;
  }
  std::mutex Mutex;
  std::string Text;
};

/// Runs on the worker thread inside RequestData: publishes the progress and
/// turns a Cancel into AbortExecute (set here, not from the UI thread, because
/// the pipeline clears AbortExecute when it starts executing).
struct ProgressWatcher : vtkCommand
{
  static ProgressWatcher* New() { return new ProgressWatcher; }
  void Execute(vtkObject* caller, unsigned long, void* data) override
  {
    if (data)
      this->Fraction.store(*static_cast<double*>(data));
    if (this->Cancel.load())
      static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
  }
  std::atomic<double> Fraction{ 0.0 };
  std::atomic<bool> Cancel{ false };
};
} // namespace

int meshSignModeFromName(const QString& name)
{
  // the CLI's parser: the same names, the same error
  switch (lvdif::signModeFromName(name.toStdString(), "--mesh-sign"))
  {
    case lvdif::SignMode::Normal: return vtkMeshToSDF::NORMAL;
    case lvdif::SignMode::PseudoNormal: return vtkMeshToSDF::PSEUDO_NORMAL;
    case lvdif::SignMode::Unsigned: return vtkMeshToSDF::UNSIGNED;
    case lvdif::SignMode::WindingNumber: break;
  }
  return vtkMeshToSDF::WINDING_NUMBER;
}

bool askMeshImportSettings(QWidget* parent, MeshImportSettings& settings)
{
  QDialog dlg(parent);
  dlg.setWindowTitle("Open mesh");
  auto* form = new QFormLayout(&dlg);
  auto* resolution = new QSpinBox(&dlg);
  // every fitted grid's range, the padding's least (as --mesh-resolution and lvdif mesh-to-sdf --dims)
  resolution->setRange(settings.leastResolution(), static_cast<int>(lvdif::DictionaryVolume::MaxDimension));
  resolution->setValue(settings.resolution);
  resolution->setToolTip("Voxels along the mesh's longest axis");
  form->addRow("Resolution", resolution);
  auto* sign = new QComboBox(&dlg);
  sign->addItem("Winding number (robust)", int(vtkMeshToSDF::WINDING_NUMBER));
  sign->addItem("Pseudo-normal", int(vtkMeshToSDF::PSEUDO_NORMAL));
  sign->addItem("Face normal (the paper's)", int(vtkMeshToSDF::NORMAL));
  sign->setCurrentIndex(sign->findData(settings.signMode));
  form->addRow("Sign", sign);
  // the option the reversed-faces warning names (winding sign only)
  auto* reorient = new QCheckBox("Re-orient faces", &dlg);
  reorient->setChecked(settings.reorientFaces);
  reorient->setToolTip("Orient each connected part's faces consistently and count duplicate faces once: for scans "
                       "and exports whose face orientation cannot be trusted (winding number sign)");
  auto enableReorient = [sign, reorient] {
    reorient->setEnabled(sign->currentData().toInt() == int(vtkMeshToSDF::WINDING_NUMBER));
  };
  enableReorient();
  QObject::connect(sign, QOverload<int>::of(&QComboBox::currentIndexChanged), reorient, enableReorient);
  form->addRow("", reorient);
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel, &dlg);
  form->addRow(buttons);
  QObject::connect(buttons, &QDialogButtonBox::accepted, &dlg, &QDialog::accept);
  QObject::connect(buttons, &QDialogButtonBox::rejected, &dlg, &QDialog::reject);
  if (dlg.exec() != QDialog::Accepted)
    return false;
  settings.resolution = resolution->value();
  settings.signMode = sign->currentData().toInt();
  settings.reorientFaces = reorient->isChecked();
  return true;
}

std::shared_ptr<lvdif::DictionaryVolume> importMesh(
  QWidget* parent, const QString& path, const MeshImportSettings& settings, QString& error, QString* warning,
  lvdif::Interrupter* console)
{
  error.clear();
  if (warning)
    warning->clear();
  vtkNew<vtkLVDIFMeshReader> reader;
  reader->SetFileName(path.toLocal8Bit().constData());
  vtkNew<vtkMeshToSDF> toSdf;
  toSdf->SetInputConnection(reader->GetOutputPort());
  toSdf->SetMaxDimension(settings.resolution);
  toSdf->SetSignMode(settings.signMode);
  toSdf->SetPadding(settings.padding);
  toSdf->SetReorientFaces(settings.reorientFaces && settings.signMode == vtkMeshToSDF::WINDING_NUMBER);
  vtkNew<ErrorCollector> errors;
  for (vtkAlgorithm* a : { static_cast<vtkAlgorithm*>(reader), static_cast<vtkAlgorithm*>(toSdf) })
  {
    a->AddObserver(vtkCommand::ErrorEvent, errors);
    a->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
  }
  // the filter's warnings (a mesh that encloses no volume, voxels too coarse, reversed faces)
  vtkNew<ErrorCollector> warnings;
  toSdf->AddObserver(vtkCommand::WarningEvent, warnings);
  vtkNew<ProgressWatcher> progress;
  toSdf->AddObserver(vtkCommand::ProgressEvent, progress);

  std::shared_ptr<lvdif::DictionaryVolume> volume;
  std::string failure;
  std::atomic<bool> done{ false };
  std::thread worker([&] {
    try
    {
      if (settings.cubic)
      {
        // As `lvdif mesh-to-sdf --out X.bv`: the grid fitted to the mesh made
        // cubic, the resolution on every axis around the same centre and
        // voxels (the conversion made a 22 x 32 x 22 grid, and the .bv save
        // failed after it). The grid is fitted as vtkMeshToSDF fits it: to
        // the mesh's bounds.
        reader->Update();
        vtkDataSet* mesh = vtkDataSet::SafeDownCast(reader->GetOutputDataObject(0));
        if (mesh && mesh->GetNumberOfPoints() > 0) // else the filter reports the reader's error
        {
          double b[6];
          mesh->GetBounds(b);
          lvdif::TriangleMesh box;
          for (int c = 0; c < 8; ++c)
            box.points.push_back({ static_cast<float>(b[(c & 1) ? 1 : 0]), static_cast<float>(b[(c & 2) ? 3 : 2]),
              static_cast<float>(b[(c & 4) ? 5 : 4]) });
          box.triangles.push_back({ 0, 1, 2 });
          lvdif::GridGeometry g = lvdif::fitGridToMesh(box, settings.resolution, settings.padding);
          int dims[3];
          double origin[3], spacing[3];
          for (int a = 0; a < 3; ++a)
          {
            origin[a] = g.origin[a] - 0.5 * static_cast<double>(settings.resolution - g.dims[a]) * g.spacing[a];
            dims[a] = settings.resolution;
            spacing[a] = g.spacing[a];
          }
          toSdf->SetUseExplicitGrid(true);
          toSdf->SetDimensions(dims);
          toSdf->SetOrigin(origin);
          toSdf->SetSpacing(spacing);
        }
      }
      toSdf->Update();
      auto* sparse = vtkSparseDictionaryVolume::SafeDownCast(toSdf->GetOutputDataObject(0));
      if (sparse && !progress->Cancel.load())
      {
        volume = sparse->GetVolume(); // shared with the filter's output, which goes away with it
      }
    }
    catch (const std::exception& e)
    {
      failure = e.what();
    }
    done.store(true);
  });

  // The UI thread waits in its own event loop: the dialog repaints and Cancel works.
  QProgressDialog dlg("Converting " + path + " to a volume...", "Cancel", 0, 1000, parent);
  dlg.setWindowTitle("Open mesh");
  dlg.setWindowModality(Qt::WindowModal);
  dlg.setMinimumDuration(300);
  QEventLoop loop;
  QTimer timer;
  if (console)
    console->start("mesh to SDF"); // the CLI's stage name
  QObject::connect(&timer, &QTimer::timeout, [&] {
    if (dlg.wasCanceled() || (console && console->wasInterrupted()))
      progress->Cancel.store(true);
    dlg.setValue(static_cast<int>(1000 * progress->Fraction.load()) % 1000);
    if (console)
      console->progress(progress->Fraction.load());
    if (done.load())
      loop.quit();
  });
  timer.start(30);
  loop.exec();
  worker.join();
  dlg.reset();
  if (console && volume && !progress->Cancel.load())
    console->end(); // "mesh to SDF: done" only when it is (a failure prints its error alone)

  if (progress->Cancel.load())
    return nullptr; // cancelled: error stays empty
  if (!volume)
  {
    const std::string why = !failure.empty() ? failure : errors->text();
    error = QString::fromStdString(why.empty() ? std::string("the conversion produced no volume") : why);
  }
  else if (warning)
  {
    *warning = QString::fromStdString(warnings->text());
  }
  return volume;
}
