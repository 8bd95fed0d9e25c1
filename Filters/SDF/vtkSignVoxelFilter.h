/**
 * @class   vtkSignVoxelFilter
 * @brief   repairs wrong signs of a sparse volume or signed distance image (LVDIF's SVF1..SVF4)
 *
 * Input, one of:
 * - a vtkSparseDictionaryVolume: filtered by Core (lvdif::signVoxelFilter on
 *   the dictionary volume, streamed by slabs of planes: no dense copy, uniform
 *   chunks stay collapsed) in a copy-on-write clone of the Core volume: the
 *   input is not modified, and the output shares every chunk the filters did
 *   not change with it (only the changed chunks are copied). The output is a
 *   vtkSparseDictionaryVolume whose dirty flags mark the chunks whose signs changed;
 * - a vtkImageData, as follows.
 *
 * Runs the sign voxel filters of Wang et al. 2023 ("LVDIF", Sect. 3.2) on one
 * float point array of a vtkImageData (chosen with SetInputArrayToProcess;
 * default: the array named `sdf`), negative inside, in voxel units. The
 * output is the input with that array replaced by a filtered copy; the input
 * is not modified. Field data of the output gets `svf_flips` (vtkIdTypeArray,
 * 4 values: voxels whose sign SVF1..SVF4 changed) and `svf_iterations`
 * (vtkIntArray, 4 values). Rules, parameters and determinism: docs/SVF.md and
 * lvdif/SignVoxelFilter.h. Reports progress; AbortExecute cancels (the output
 * is then empty).
 *
 * Sparse input under MPI (a controller with more than one process, e.g.
 * pvbatch): rank r of n owns the chunk layers [r L / n, (r + 1) L / n) of the
 * L layers of storage chunks along the filter axis. It asks its input for its
 * layers plus one ghost plane on each side (the .lvdv reader then loads only
 * those chunks), filters only its own planes in a copy-on-write clone, and
 * needs from the other ranks only one exchange: the sign each row leaves
 * their layers with after SVF1 (lvdif::svf1ExitSigns, all-gathered, then
 * composed from rank 0 upwards), because SVF2/SVF3 stay inside one plane and
 * SVF4 reads one plane on each side, which the rank filters itself. Then
 * each rank sends the filtered chunks that overlap another rank's requested
 * extent to it (the marching cubes asks for its block plus one ghost layer),
 * so every rank's output holds exactly the chunks its consumer asked for, as
 * the serial result has them; chunks outside that extent are dropped
 * (uniform). A generic filter's piece request (ParaView's Contour) gets the
 * block of chunks the .lvdv reader would give it (LVDIFVolumeBridge::PieceChunks).
 * The statistics are summed over the ranks. Field data `svf_piece`
 * (vtkIdTypeArray): rank, ranks, first and last plane filtered here, the
 * input's and the output's expanded chunks.
 *
 * Image input, pieces: SVF1 scans whole rows and SVF2/SVF3 sweep whole planes,
 * so a piece filtered alone would read its cut as the volume's boundary. The
 * filter therefore asks its input for the WHOLE extent (as vtkProbeFilter
 * does for its source), filters all of it and outputs only the requested
 * update extent: every piece equals the same region of the serial result
 * (correct, not scalable: each rank holds and filters the whole image).
 */
#ifndef vtkSignVoxelFilter_h
#define vtkSignVoxelFilter_h

#include "lvdifFiltersSDFModule.h"
#include "vtkDataObjectAlgorithm.h"

class vtkMultiProcessController;
class vtkSparseDictionaryVolume;
#include <memory>

namespace lvdif
{
class DictionaryVolume;
struct SignVoxelFilterParams;
struct SignVoxelFilterStats;
}

class LVDIFFILTERSSDF_EXPORT vtkSignVoxelFilter : public vtkDataObjectAlgorithm
{
public:
  static vtkSignVoxelFilter* New();
  vtkTypeMacro(vtkSignVoxelFilter, vtkDataObjectAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum
  {
    SVF1 = 1,
    SVF2 = 2,
    SVF3 = 4,
    SVF4 = 8,
    ALL = 15
  };
  enum
  {
    BOUNDARY_OUTSIDE = 0,
    BOUNDARY_FREE = 1
  };
  enum
  {
    DEVICE_AUTO = 0,
    DEVICE_CPU = 1,
    DEVICE_CUDA = 2
  };

  ///@{
  /// SVF1..SVF3 never flip voxels with |value| <= Threshold (default 2, voxel units).
  /// Negative, NaN, infinite or beyond float is an error at update, never clamped
  /// (Core's rule: lvdif::checkSignVoxelFilterParams); GetThreshold returns what was set.
  vtkSetMacro(Threshold, double);
  vtkGetMacro(Threshold, double);
  ///@}

  ///@{
  /// Filter axis 0 = x (default), 1 = y, 2 = z; anything else is an error at update.
  vtkSetMacro(Axis, int);
  vtkGetMacro(Axis, int);
  ///@}

  ///@{
  /// Bit mask of the filters to run (SVF1 | SVF2 | SVF3 | SVF4; default ALL);
  /// other bits are an error at update.
  vtkSetMacro(Filters, int);
  vtkGetMacro(Filters, int);
  ///@}

  ///@{
  /// One filter of the mask on or off (ParaView's checkboxes set these).
  void SetUseSVF1(bool on) { this->SetFilterBit(SVF1, on); }
  bool GetUseSVF1() { return (this->Filters & SVF1) != 0; }
  void SetUseSVF2(bool on) { this->SetFilterBit(SVF2, on); }
  bool GetUseSVF2() { return (this->Filters & SVF2) != 0; }
  void SetUseSVF3(bool on) { this->SetFilterBit(SVF3, on); }
  bool GetUseSVF3() { return (this->Filters & SVF3) != 0; }
  void SetUseSVF4(bool on) { this->SetFilterBit(SVF4, on); }
  bool GetUseSVF4() { return (this->Filters & SVF4) != 0; }
  ///@}

  ///@{
  /// SVF2/SVF3 iterations per plane at most; 0 = automatic (default); negative
  /// is an error at update.
  vtkSetMacro(MaxIterations, int);
  vtkGetMacro(MaxIterations, int);
  ///@}

  ///@{
  /// What the neighbours outside the image read as: BOUNDARY_OUTSIDE (default)
  /// or BOUNDARY_FREE (no sign); anything else is an error at update (no clamp).
  vtkSetMacro(Boundary, int);
  vtkGetMacro(Boundary, int);
  ///@}

  ///@{
  /// The ranks of a distributed run (default: the global controller; none or
  /// one process: serial).
  void SetController(vtkMultiProcessController* c);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  ///@}

  ///@{
  /// DEVICE_AUTO (default: CUDA when available), DEVICE_CPU or DEVICE_CUDA;
  /// anything else is an error at update (LVDIFVolumeBridge::DeviceOption; no clamp).
  vtkSetMacro(Device, int);
  vtkGetMacro(Device, int);
  ///@}

protected:
  vtkSignVoxelFilter();
  ~vtkSignVoxelFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestDataObject(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  /// RequestData: Produce, and a failure (always after its one error, or a
  /// cancel) marked reported (LVDIFVolumeBridge::FailReported: no executive
  /// "returned failure for request" dump after it).
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int Produce(vtkInformationVector** inputVector, vtkInformationVector* outputVector);
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  void SetFilterBit(int bit, bool on) { this->SetFilters(on ? (this->Filters | bit) : (this->Filters & ~bit)); }

  lvdif::SignVoxelFilterParams CoreParams() const;
  int FilterSparse(vtkSparseDictionaryVolume* input, vtkSparseDictionaryVolume* output, vtkInformation* outInfo);
  /// True when the sparse path runs as one of several ranks (Controller with > 1 process).
  bool Distributed() const;
  /// The sparse path on one rank of several (see the class comment).
  bool FilterSparsePiece(const lvdif::DictionaryVolume& input, vtkInformation* outInfo, int ownedChunks[6],
    std::shared_ptr<lvdif::DictionaryVolume>& volume, lvdif::SignVoxelFilterStats& stats);

  /// A distributed sparse pass's first collective (RequestInformation, then
  /// RequestData): every rank says whether it can go on; false on every rank
  /// when one cannot. A rank whose input failed upstream never runs those
  /// methods: the filter's executive joins for it (see the .cxx), so the
  /// other ranks do not wait for it forever.
  bool JoinRanks(bool ok);
  /// The same collective with a state (JOIN_FAILED, JOIN_EMPTY: the input holds
  /// no volume, JOIN_READY): the lowest and highest state over the ranks.
  enum JoinState
  {
    JOIN_FAILED = 0,
    JOIN_EMPTY = 1,
    JOIN_READY = 2
  };
  void JoinRanks(int state, int& lowest, int& highest);
  /// Whether this pass meets the other ranks: distributed and a sparse input.
  bool MeetsRanks(vtkInformationVector** inputVector) const;
  bool Joined = false; // this pass reached JoinRanks
  vtkExecutive* CreateDefaultExecutive() override;
  friend class vtkSignVoxelFilterExecutive;

  vtkMultiProcessController* Controller = nullptr;

  double Threshold = 2.0;
  int Axis = 0;
  int Filters = ALL;
  int MaxIterations = 0;
  int Boundary = BOUNDARY_OUTSIDE;
  int Device = DEVICE_AUTO;

private:
  vtkSignVoxelFilter(const vtkSignVoxelFilter&) = delete;
  void operator=(const vtkSignVoxelFilter&) = delete;
};

#endif
