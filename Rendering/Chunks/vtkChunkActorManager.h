/**
 * @class   vtkChunkActorManager
 * @brief   one actor per marching cubes chunk; replacing a chunk re-uploads
 *          only that chunk's buffers
 *
 * The paper (Sect. 3.3, 3.4.1) re-meshes only the chunks a brush touched and
 * updates only their mesh objects. Here each chunk id owns a vtkActor with a
 * vtkTetrahedralColorMapper. SetChunk() swaps the input of that one mapper,
 * so the next render uploads that chunk's vertex buffers and no other; an
 * empty mesh removes the actor. All actors share one vtkProperty.
 *
 * Why not one merged actor: rebuilding a merged poly data and re-uploading it
 * costs time proportional to the whole model per edit (see
 * Testing/Benchmarks/VTK/bench_chunk_actors.cxx for the measured ratio); the
 * price of one actor per chunk is one draw call per non-empty chunk, which
 * stays small with 32^3..64^3 cell chunks (a 512^3 volume has at most 4096).
 *
 * Input meshes either carry the tetrahedral contract (cell data
 * `corner_rgba`, `cell_ijk`), in which case they are run through
 * vtkCornerColorAttributes with the volume geometry set here, or just point
 * data `rgba` + `Normals` (per-vertex colours).
 *
 * Not thread-safe: call from the thread that renders. PrepareChunk() is the
 * part that may run on a worker thread.
 */
#ifndef vtkChunkActorManager_h
#define vtkChunkActorManager_h

#include "lvdifRenderingChunksModule.h" // for export macro
#include "vtkObject.h"
#include "vtkSmartPointer.h" // for return type

#include <memory>  // for unique_ptr
#include <vector>  // for SetChunks

class vtkActor;
class vtkPartialRedrawCuller;
class vtkPartitionedDataSet;
class vtkPolyData;
class vtkProp;
class vtkProperty;
class vtkRenderer;
class vtkTexture;

class LVDIFRENDERINGCHUNKS_EXPORT vtkChunkActorManager : public vtkObject
{
public:
  static vtkChunkActorManager* New();
  vtkTypeMacro(vtkChunkActorManager, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The renderer the chunk actors live in (actors move over when it changes).
  void SetRenderer(vtkRenderer* renderer);
  vtkRenderer* GetRenderer();

  ///@{
  /// Volume geometry (world position of voxel (0,0,0), voxel size) used to
  /// turn cell_ijk into local cell coordinates.
  vtkSetVector3Macro(Origin, double);
  vtkGetVector3Macro(Origin, double);
  vtkSetVector3Macro(Spacing, double);
  vtkGetVector3Macro(Spacing, double);
  ///@}

  /// vtkTetrahedralColorMapper::Tetrahedral (default) or ::PerVertex, for every chunk.
  void SetInterpolationMode(int mode);
  vtkGetMacro(InterpolationMode, int);

  /// The property every chunk actor shares (material, opacity, ...).
  vtkProperty* GetProperty();

  /// Matcap shading of every chunk with this image (vtkTetrahedralColorMapper's
  /// Matcap: the image's colour at the view-space normal times the surface
  /// colour, no scene lights); nullptr: lit as usual. The texture goes on the
  /// shared property under vtkTetrahedralColorMapper::MatcapTextureName().
  void SetMatcapTexture(vtkTexture* texture);
  vtkTexture* GetMatcapTexture();

  /// Prepares a mesh for rendering (un-shares vertices for the tetrahedral
  /// shader when the mesh carries corner colours; the coordinates' ranges,
  /// which the buffer upload and the mapper's bounds use, cached in their
  /// array). Thread-safe for distinct meshes; SetChunk calls it unless told
  /// the mesh is prepared.
  vtkSmartPointer<vtkPolyData> PrepareChunk(vtkPolyData* mesh) const;

  /// Replaces the mesh of one chunk. A null or empty mesh removes the chunk.
  /// A mesh equal, value for value, to the one the chunk shows
  /// (lvdif::render::sameMesh: points, point and cell arrays, cells), given
  /// as another object while the shown one is unmodified and the geometry
  /// (origin, spacing) is the one it was prepared with, leaves the chunk as it
  /// is: nothing is prepared, uploaded or redrawn (NumberOfUnchangedMeshes).
  void SetChunk(vtkIdType chunkId, vtkPolyData* mesh, bool prepared = false);
  /// SetChunk of each (id, mesh) in order (an equal mesh of a chunk named once
  /// left as shown, as in SetChunk), the meshes prepared (and their
  /// changes measured) in parallel (vtkSMPTools): a frame's re-meshed chunks.
  /// A mesh object is read by one thread at a time (one given twice makes the
  /// call prepare on this thread).
  void SetChunks(const std::vector<vtkIdType>& chunkIds, const std::vector<vtkPolyData*>& meshes);
  void RemoveChunk(vtkIdType chunkId);
  /// Shows every partition of vtkChunkedMarchingCubes' partitioned output
  /// (field data `chunk_id` names the chunk; partitions without it get their
  /// index). Chunks not in the data set are removed; a partition whose poly
  /// data object was already shown for that chunk is not re-uploaded.
  void SetPartitions(vtkPartitionedDataSet* chunks);
  void RemoveAllChunks();

  vtkActor* GetChunkActor(vtkIdType chunkId);
  /// The chunk id of an actor of this manager (e.g. a picked one), or -1.
  vtkIdType GetChunkId(vtkProp* actor);
  int GetNumberOfChunks();
  vtkIdType GetNumberOfTriangles();
  /// Bounds of every chunk actor (vtkMath::UninitializeBounds if none).
  void GetBounds(double bounds[6]);
  /// Every chunk mesh (as given, before preparation) appended into one poly data
  /// (for export and for the merged-actor comparison).
  vtkSmartPointer<vtkPolyData> GetMergedMesh();
  /// How many times a chunk's mesh was replaced or added since construction.
  vtkGetMacro(NumberOfChunkUpdates, vtkIdType);
  /// How many meshes given to SetChunk/SetChunks equalled their chunk's shown
  /// mesh and were left as shown (not counted in NumberOfChunkUpdates).
  vtkGetMacro(NumberOfUnchangedMeshes, vtkIdType);

  void SetVisibility(bool visible);

  /// vtkTetrahedralColorMapper::SetDrawRangeTriangles for every chunk (default
  /// 32; 0: each chunk drawn with one call): a frame drawn in part draws only
  /// the ranges of a chunk's triangles whose screen rectangles meet its scissor
  /// box. Chunks are prepared with their triangles in Morton order
  /// (vtkCornerColorAttributes::SpatialOrder), so a range lies in a few cells.
  void SetDrawRangeTriangles(int triangles);
  vtkGetMacro(DrawRangeTriangles, int);

  /// The triangles the chunk actors drew in their last renders, summed over the
  /// chunks that the renderer's last frame drew (those whose mappers rendered
  /// at its time or later), and their draw calls.
  vtkIdType GetLastNumberOfTrianglesDrawn(int* drawCalls = nullptr);

  /// The renderer's partial-redraw culler, if any: SetChunk then declares a
  /// replaced mesh's change to it as the box of the triangles that differ
  /// (vtkPartialRedrawCuller::BeginChange/EndChange), so that a frame redraws
  /// only around them rather than around the whole chunk. The chunk actors'
  /// inputs change only here, so they are the culler's announced actors
  /// (vtkPartialRedrawCuller::SetInputChangesAnnounced): a frame does not read
  /// the unchanged chunks' inputs' MTimes.
  void SetRedrawCuller(vtkPartialRedrawCuller* culler);

  /// The bounds of the triangles of one mesh that the other lacks, and of the
  /// other's that the first lacks, comparing each triangle's points (position
  /// and every point array, any starting vertex) and cell arrays; false if
  /// they hold the same triangles. Meshes with cells other than triangles
  /// compare whole (their union's bounds).
  static bool ChangedBounds(vtkPolyData* before, vtkPolyData* after, double bounds[6]);

protected:
  vtkChunkActorManager();
  ~vtkChunkActorManager() override;

  double Origin[3] = { 0, 0, 0 };
  double Spacing[3] = { 1, 1, 1 };
  int InterpolationMode = 0;
  int DrawRangeTriangles = 32;
  vtkIdType NumberOfChunkUpdates = 0;
  vtkIdType NumberOfUnchangedMeshes = 0;

private:
  vtkChunkActorManager(const vtkChunkActorManager&) = delete;
  void operator=(const vtkChunkActorManager&) = delete;

  /// Shows `ready` (prepared from `mesh`; `owned`: made here, may be refilled
  /// into the next time) for a chunk; `hashes`: triangleHashes of `mesh`, if known.
  /// `change`: the changed triangles' bounds and points against the chunk's
  /// current mesh, if SetChunks measured them in its parallel part.
  struct Hashes;
  struct Change;
  void ApplyChunk(vtkIdType chunkId, vtkPolyData* mesh, vtkPolyData* ready, bool owned, Hashes* hashes,
    const Change* change = nullptr);
  /// Whether the chunk shows a mesh equal to `mesh` (see SetChunk), so that it may stay as it is.
  bool ShowsEqualMesh(vtkIdType chunkId, vtkPolyData* mesh);
  /// triangleHashes of `mesh`, sorted with their triangles' indices; false if it has cells other than triangles.
  static bool hashesOf(vtkPolyData* mesh, Hashes& out);

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
