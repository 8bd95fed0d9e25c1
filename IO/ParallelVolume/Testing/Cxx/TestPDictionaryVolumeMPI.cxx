// Under `mpirun -np 2`: the ranks of a .lvdvp write agree on success even when
// one rank's input fails upstream (its WriteData never runs). Before, the
// other rank waited in the all-reduce for it forever (the test timed out).
// Also the good case: both pieces and the index are written, and a failed
// index (piece 0's) fails every rank's Write(); NumberOfPieces unlike the
// Controller's processes is refused before anything is written. A piece file
// one rank cannot write is refused by every rank before any input runs (the
// ranks agree first; before, both ran their input and only then refused).
#include "MPITestUtil.h"
#include "vtkDictionaryVolumeReader.h"
#include "vtkCommand.h"
#include "vtkNew.h"
#include "vtkPDictionaryVolumeWriter.h"

#include "lvdif/DictionaryVolume.h"
#include "lvdif/VolumeFile.h"

#include <cstdio>
#include <string>
#include <sys/stat.h>

namespace
{
bool exists(const std::string& path)
{
  struct stat st;
  return ::stat(path.c_str(), &st) == 0;
}

struct Counter : vtkCommand
{
  static Counter* New() { return new Counter; }
  void Execute(vtkObject*, unsigned long, void*) override { ++this->Count; }
  int Count = 0;
};

/// Every rank writes its piece of `index` from `input`; returns Write()'s
/// answer (and in `runs` how often this rank's reader ran).
int writePieces(vtkMultiProcessController* c, const std::string& input, const std::string& index, int* runs = nullptr)
{
  vtkNew<Counter> counter;
  vtkNew<vtkDictionaryVolumeReader> reader;
  reader->AddObserver(vtkCommand::StartEvent, counter);
  reader->SetFileName(input.c_str());
  vtkNew<vtkPDictionaryVolumeWriter> writer;
  writer->SetInputConnection(reader->GetOutputPort());
  writer->SetFileName(index.c_str());
  writer->SetController(c);
  writer->SetNumberOfPieces(c->GetNumberOfProcesses());
  writer->SetPiece(c->GetLocalProcessId());
  const int written = writer->Write();
  if (runs)
    *runs = counter->Count;
  return written;
}
}

int main(int argc, char* argv[])
{
  MPITestRun run(&argc, &argv);
  vtkMPIController* c = run.controller();
  const int rank = run.rank();
  if (argc < 2 || run.ranks() != 2)
    return run.usage("mpirun -np 2 TestPDictionaryVolumeMPI DIR");
  const std::string dir = argv[1];
  const std::string good = dir + "/mpi_input.lvdv", missing = dir + "/mpi_missing.lvdv";
  const std::string okIndex = dir + "/mpi_ok.lvdvp", failedIndex = dir + "/mpi_failed.lvdvp";
  if (rank == 0)
  {
    ::mkdir(dir.c_str(), 0755);
    std::remove(okIndex.c_str());
    std::remove(failedIndex.c_str());
    std::remove(missing.c_str());
    lvdif::VolumeOptions o;
    o.dims = { 24, 20, 16 };
    o.chunkEdge = 8;
    lvdif::saveVolume(lvdif::DictionaryVolume(o), good);
  }
  c->Barrier();

  run.check(writePieces(c, good, okIndex) == 1, "both inputs good: Write() answers 1");
  run.check(exists(okIndex), "both inputs good: the index exists");
  // written again: every rank puts its piece in the generation the index does not
  // list, piece 0 switches the index and removes the old pieces (docs/FORMAT.md)
  run.check(writePieces(c, good, okIndex) == 1, "written again: Write() answers 1");
  for (int p = 0; p < 2; ++p)
  {
    run.check(exists(vtkPDictionaryVolumeWriter::PieceFilePath(okIndex, p, 1)), "written again: the new pieces exist");
    run.check(!exists(vtkPDictionaryVolumeWriter::PieceFilePath(okIndex, p, 0)), "written again: the old pieces are removed");
  }

  // rank 1's reader fails (no such file): both ranks return, with 0, and no index
  vtkObject::GlobalWarningDisplayOff(); // the expected reader error, once per run is enough
  run.check(writePieces(c, rank == 1 ? missing : good, failedIndex) == 0, "one input failed: Write() answers 0");
  run.check(!exists(failedIndex), "one input failed: no index");

  // piece 0 cannot write the index (a folder has its name): every rank's
  // Write() answers 0 (before, only rank 0's did; the others answered 1)
  const std::string folderIndex = dir + "/mpi_folder.lvdvp";
  if (rank == 0)
    ::mkdir(folderIndex.c_str(), 0755);
  c->Barrier();
  run.check(writePieces(c, good, folderIndex) == 0, "the index cannot be written: Write() answers 0 on every rank");

  // rank 1's piece file cannot be written (a folder has its name): every
  // rank refuses before its input runs, and none waits for the other
  const std::string blocked = dir + "/mpi_blocked.lvdvp";
  if (rank == 0)
  {
    std::remove(blocked.c_str());
    ::mkdir(vtkPDictionaryVolumeWriter::PieceFilePath(blocked, 1, 0).c_str(), 0755);
  }
  c->Barrier();
  int runs = -1;
  run.check(writePieces(c, good, blocked, &runs) == 0, "a piece file cannot be written: Write() answers 0 on every rank");
  run.check(runs == 0, "a piece file cannot be written: no rank's input ran");
  run.check(!exists(blocked), "a piece file cannot be written: no index");

  // NumberOfPieces 3 on a Controller of 2 processes: each rank would write
  // every piece; refused on every rank before anything is written
  const std::string mismatch = dir + "/mpi_mismatch.lvdvp";
  if (rank == 0) // what an earlier run left
  {
    std::remove(mismatch.c_str());
    for (int p = 0; p < 3; ++p)
      std::remove(vtkPDictionaryVolumeWriter::PieceFilePath(mismatch, p).c_str());
  }
  c->Barrier();
  {
    vtkNew<vtkDictionaryVolumeReader> reader;
    reader->SetFileName(good.c_str());
    vtkNew<vtkPDictionaryVolumeWriter> writer;
    writer->SetInputConnection(reader->GetOutputPort());
    writer->SetFileName(mismatch.c_str());
    writer->SetController(c);
    writer->SetNumberOfPieces(3);
    writer->SetPiece(rank);
    run.check(writer->Write() == 0, "NumberOfPieces 3 on 2 processes: Write() answers 0");
  }
  c->Barrier();
  bool none = !exists(mismatch);
  for (int p = 0; p < 3; ++p)
    none = none && !exists(vtkPDictionaryVolumeWriter::PieceFilePath(mismatch, p));
  run.check(none, "NumberOfPieces 3 on 2 processes: nothing written");

  return run.finish("PDictionaryVolume MPI OK");
}
