/**
 * @class   vtkPDictionaryVolumeWriter
 * @brief   writes a distributed image or sparse volume as one .lvdv file per piece plus a .lvdvp index
 *
 * A vtkSparseDictionaryVolume input is cropped to the piece's extent keeping
 * its keys and chunk edge (nothing re-encoded; BandWidth and ChunkEdge then
 * do not apply).
 * Every process writes its piece (Piece of NumberOfPieces; ParaView sets both
 * from the MPI rank and size) as `<name>_<piece>.lvdv` or `<name>_<piece>.g1.lvdv`
 * (the generation the current index does not list: NextGeneration) beside FileName
 * (`<name>.lvdvp`), with vtkDictionaryVolumeWriter's encoding (BandWidth,
 * ChunkEdge, CompressionLevel). Piece 0 writes the index: a small text file
 * with the format version, the whole extent, origin, spacing and each
 * non-empty piece's extent and file (docs/FORMAT.md, "Distributed volumes").
 *
 * The writer asks its input for exactly the extent vtkExtentTranslator gives
 * the piece (block mode, no ghosts), so piece 0 knows every piece's extent
 * without communication; pieces share one point plane per cut, as ParaView's.
 * A sparse volume's piece is instead the block of storage chunks its producer
 * computes for that piece (LVDIFVolumeBridge::PieceChunks, the readers' rule)
 * plus the point layer shared with the next chunks: the points' split differs
 * from the chunks' in general, and took voxels never computed for the piece.
 * With a Controller of NumberOfPieces processes the ranks agree on success
 * (the index is written only if every piece was) and wait for each other, so
 * the index is complete when Write() returns. In a serial run (no Controller,
 * or one of one process) Write() writes every piece and then the index from
 * the whole input (Piece is not used), as VTK's XML parallel writers do in
 * one process: it wrote only piece 0 and an index that listed all pieces.
 * Every file is checked writable before the first is written, and the index
 * (and with it the volume a reader sees) is replaced only when every piece
 * was written. A Controller of several processes but not NumberOfPieces is
 * refused before anything is written (each rank would write every piece).
 * A rank whose input fails upstream (WriteData never runs there) or that
 * refuses its settings still joins the agreement, as a failed piece: every
 * rank's Write() then returns 0, none waits for it. When piece 0 cannot
 * write the index, every rank's Write() returns 0 too.
 *
 * vtkPDictionaryVolumeReader reads the index (only the pieces overlapping its
 * update extent).
 */
#ifndef vtkPDictionaryVolumeWriter_h
#define vtkPDictionaryVolumeWriter_h

#include "lvdifIOParallelVolumeModule.h"
#include "vtkWriter.h"

#include <string>

class vtkImageData;
class vtkSparseDictionaryVolume;
class vtkMultiProcessController;

class LVDIFIOPARALLELVOLUME_EXPORT vtkPDictionaryVolumeWriter : public vtkWriter
{
public:
  static vtkPDictionaryVolumeWriter* New();
  vtkTypeMacro(vtkPDictionaryVolumeWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// vtkWriter::Write, but 0 when the input failed upstream (as every LVDIF
  /// writer: vtkLVDIFVolumeWriter::UpdateWholeInput).
  int Write() override;

  /// The index file (`name.lvdvp`); pieces go to `name_<piece>.lvdv` beside it.
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);

  ///@{
  /// This process's piece and the number of pieces (default 0 of 1); a piece
  /// outside [0, NumberOfPieces - 1] is an error at write, nothing written (no clamp).
  /// A serial run writes all NumberOfPieces pieces (see the class comment).
  vtkSetMacro(Piece, int);
  vtkGetMacro(Piece, int);
  vtkSetMacro(NumberOfPieces, int);
  vtkGetMacro(NumberOfPieces, int);
  ///@}

  ///@{
  /// Encoding of every piece, as vtkDictionaryVolumeWriter's.
  vtkSetMacro(BandWidth, double);
  vtkGetMacro(BandWidth, double);
  vtkSetMacro(ChunkEdge, int);
  vtkGetMacro(ChunkEdge, int);
  vtkSetMacro(CompressionLevel, int); // 1..19, else an error at write (no clamp)
  vtkGetMacro(CompressionLevel, int);
  vtkSetStdStringFromCharMacro(VolumeName);
  vtkGetCharFromStdStringMacro(VolumeName);
  ///@}

  ///@{
  /// The controller the ranks agree through (default: the global controller).
  /// Used only when it has exactly NumberOfPieces processes.
  virtual void SetController(vtkMultiProcessController*);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  ///@}

  vtkImageData* GetInput();

  /// The extent of `piece` of `numberOfPieces` of `wholeExtent` (the translator's block split, no ghosts).
  static void PieceExtent(const int wholeExtent[6], int piece, int numberOfPieces, int extent[6]);

  /// The file of piece `piece` of generation `generation` beside the index
  /// `indexPath`: name_<piece>.lvdv (generation 0), name_<piece>.g1.lvdv (1).
  static std::string PieceFilePath(const std::string& indexPath, int piece, int generation = 0);
  /// The generation a write to `indexPath` puts its pieces in: the one the
  /// current index does not list (0 when there is none or it cannot be read).
  /// The pieces are written there crash-safely, then the index is replaced
  /// (the one switch), then the set's piece files the new index does not list
  /// are removed: a write that fails at any point keeps the old index and its
  /// pieces whole. A write first removes the temporary files that killed
  /// writes of the set left (lvdif::removeStaleTemporaries).
  static int NextGeneration(const std::string& indexPath);
  /// Throws lvdif::Error when `indexPath` does not exist yet but files beside it are
  /// named as pieces of its set (name_<digits>.lvdv, name_<digits>.g1.lvdv): no index
  /// lists them, so they may be another volume's (scan_1.lvdv, scan_2.lvdv), and the
  /// first write of the set would overwrite or remove them. Checked before any work by
  /// the front ends (LVDIFFiles::RequireWritable) and by Write().
  static void RequireNoUnlistedPieces(const std::string& indexPath);

protected:
  vtkPDictionaryVolumeWriter();
  ~vtkPDictionaryVolumeWriter() override;

  vtkTypeBool ProcessRequest(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  void WriteData() override;
  int FillInputPortInformation(int port, vtkInformation* info) override;

  std::string FileName;
  std::string VolumeName;
  int Piece = 0;
  int NumberOfPieces = 1;
  double BandWidth = 8.0;
  int ChunkEdge = 32;
  int CompressionLevel;
  vtkMultiProcessController* Controller = nullptr;

private:
  /// Whether the ranks of the Controller write one piece each (collectively).
  bool IsCollective() const;
  /// Piece in [0, NumberOfPieces - 1], NumberOfPieces >= 1.
  bool PieceExists() const;
  /// The all-reduce of every rank's success (the minimum); the first of the
  /// two collective calls of a write.
  int AgreeOnPieces(int ok);
  bool Agreed = false; // this Write() reached AgreeOnPieces
  /// The second: the same all-reduce after piece 0 wrote the index (also the
  /// barrier), so that every rank knows whether the index was written.
  int AgreeOnIndex(int ok);
  /// No Controller, or one of one process: this process writes every piece.
  bool IsSerial() const;
  /// The pieces, the file name, its folder and this process's piece files
  /// (lvdif::requireWritable), the next generation and the settings (the
  /// chunk edge and band only for an image input): false after one error and
  /// the writer's error code. Run by Write() before the input is updated (the
  /// ranks agree on it first) and by WriteData.
  bool CheckTarget(bool imageInput, int& generation);
  /// Whether the input is an image (not a sparse volume): its data object's
  /// type, made by the pipeline without updating anything.
  bool InputIsImage();
  // each writes the piece to `path` (the piece's file of the new generation)
  bool WritePiece(vtkImageData* image, int piece, const int extent[6], const std::string& path);
  bool WritePiece(vtkSparseDictionaryVolume* sparse, int piece, const int extent[6], const std::string& path);
  vtkPDictionaryVolumeWriter(const vtkPDictionaryVolumeWriter&) = delete;
  void operator=(const vtkPDictionaryVolumeWriter&) = delete;
};

#endif
