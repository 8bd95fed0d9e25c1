/**
 * @class   vtkTetrahedralColorMapper
 * @brief   OpenGL poly data mapper colouring marching cubes surfaces by
 *          tetrahedral interpolation of the 8 cell corner colours
 *
 * Paper Sect. 3.4.1 (after Kasson et al.'s tetrahedral interpolation): the
 * colour of a fragment is interpolated from the 8 corner colours of the
 * marching cubes cell that produced its triangle. The unit cube is split
 * into 6 tetrahedra sharing the main diagonal (0,0,0)-(1,1,1); the fragment's
 * local cell coordinate u = (x,y,z) lies in the tetrahedron selected by the
 * order of x, y, z, and its barycentric weights in that tetrahedron weigh the
 * tetrahedron's 4 corner colours. Unlike the original shader, u is clamped
 * to [0,1]^3 so rounding cannot give negative weights.
 *
 * Input: the output of vtkCornerColorAttributes (un-shared triangles with
 * the `lvdif_cell_local` and `lvdif_corner0..7` point arrays). The mapper
 * binds them with MapDataArrayToVertexAttribute and injects GLSL through the
 * actor's vtkShaderProperty (AddVertexShaderReplacement /
 * AddFragmentShaderReplacement). Lighting stays VTK's.
 *
 * Fallback: ColorMode PerVertex, or an input without those arrays, renders
 * the point array `rgba` as direct per-vertex colours (the shader
 * replacements are removed from the actor).
 *
 * Matcap (SetMatcap): the fragment's colour is the texture that the actor's
 * property holds under the name MatcapTextureName() (see
 * vtkChunkActorManager::SetMatcapTexture), looked up at u,v = n.xy * 0.5 + 0.5
 * with n the view-space normal, times the surface colour (the diffuse colour
 * the colour code above computed); the scene's lights play no part. Without
 * that texture on the property the mapper renders lit as usual.
 *
 * Draw ranges (SetDrawRangeTriangles): the input's triangles are drawn as
 * consecutive ranges of that many triangles, each with the box of its points;
 * a range whose screen rectangle (the box projected with the camera and the
 * actor's matrix into the GL viewport, grown by DrawRangePad pixels) misses the
 * GL scissor box is not drawn. Its fragments would all fail the scissor test,
 * so the picture is the same as drawing every triangle (TestDrawRanges); what
 * is saved is the vertex work and triangle setup of software OpenGL, where a
 * partial redraw (vtkPartialRedrawCuller's scissor) otherwise draws every
 * triangle of each chunk that meets the damage. The ranges pay off when
 * consecutive triangles lie together (vtkCornerColorAttributes orders them by
 * cell in Morton order). Adjacent drawn ranges are one draw call; a frame in
 * which every range meets the scissor draws as VTK does. Only for the plain
 * case: triangles only, surface representation without edges or vertices, no
 * hardware selection or selection highlight, no cell scalars or cell normals
 * (those read gl_PrimitiveID, which restarts with each draw call); otherwise
 * VTK's draw.
 */
#ifndef vtkTetrahedralColorMapper_h
#define vtkTetrahedralColorMapper_h

#include "lvdifRenderingChunksModule.h" // for export macro
#include "vtkOpenGLPolyDataMapper.h"
#include "vtkSmartPointer.h" // for the mapper's own VBO cache

#include <vector> // for the draw ranges

class vtkOpenGLVertexBufferObjectCache;
class vtkShaderProperty;

class LVDIFRENDERINGCHUNKS_EXPORT vtkTetrahedralColorMapper : public vtkOpenGLPolyDataMapper
{
public:
  static vtkTetrahedralColorMapper* New();
  vtkTypeMacro(vtkTetrahedralColorMapper, vtkOpenGLPolyDataMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum ColorModes
  {
    Tetrahedral = 0,
    PerVertex = 1
  };
  ///@{
  /// Tetrahedral (default) or PerVertex colours.
  vtkSetClampMacro(InterpolationMode, int, Tetrahedral, PerVertex);
  vtkGetMacro(InterpolationMode, int);
  void SetInterpolationModeToTetrahedral() { this->SetInterpolationMode(Tetrahedral); }
  void SetInterpolationModeToPerVertex() { this->SetInterpolationMode(PerVertex); }
  ///@}

  /// True if the last render used the tetrahedral shader (false: fallback).
  vtkGetMacro(UsedTetrahedral, bool);

  ///@{
  /// Matcap shading (see above); off by default.
  vtkSetMacro(Matcap, bool);
  vtkGetMacro(Matcap, bool);
  ///@}
  /// The property texture name (and GLSL sampler) of the matcap image.
  static const char* MatcapTextureName() { return "lvdifMatcap"; }

  void RenderPiece(vtkRenderer* ren, vtkActor* act) override;

  ///@{
  /// Triangles per draw range (see above; default 32; 0: VTK's single draw).
  /// Not a modification: it does not change the picture.
  void SetDrawRangeTriangles(int n) { this->DrawRangeTriangles = n < 0 ? 0 : n; }
  int GetDrawRangeTriangles() const { return this->DrawRangeTriangles; }
  ///@}

  ///@{
  /// Pixels added on each side of a range's screen rectangle before it is
  /// tested against the scissor box (default 1). For tests: a negative pad
  /// skips ranges that do reach into the scissor box (a wrong picture).
  void SetDrawRangePad(int pixels) { this->DrawRangePad = pixels; }
  int GetDrawRangePad() const { return this->DrawRangePad; }
  ///@}

  ///@{
  /// Of the last render: the triangles drawn (all of them when the ranges
  /// were not used) and the number of triangle draw calls.
  vtkIdType GetLastNumberOfTrianglesDrawn() const { return this->LastTrianglesDrawn; }
  int GetLastNumberOfDrawCalls() const { return this->LastDrawCalls; }
  /// When the mapper last drew (a vtkTimeStamp value).
  vtkMTimeType GetLastDrawTime() const { return this->DrawTime.GetMTime(); }
  ///@}

  /// The bounds of the current input's cells as whoever made the input computed
  /// them (vtkChunkActorManager: where the chunks are prepared in parallel):
  /// GetBounds() returns them without a pass over the points for as long as
  /// the input object, its geometry and its cells are unchanged (its own
  /// MTime and GetMeshMTime()); after that, it computes them again.
  void SetInputBounds(const double bounds[6]);

  /// The cache of this mapper's vertex buffers: its own, not the context's
  /// (BuildBufferObjects), so that releasing them scans only its own arrays.
  vtkOpenGLVertexBufferObjectCache* GetOwnVBOCache();

  /// Installs (or with on=false removes) the tetrahedral GLSL on a shader
  /// property. Public so that other mappers of the same data can share it.
  static void InstallShaderReplacements(vtkShaderProperty* property, bool on);
  /// Installs (or removes) the matcap GLSL on a shader property.
  static void InstallMatcapReplacement(vtkShaderProperty* property, bool on);

protected:
  vtkTetrahedralColorMapper();
  ~vtkTetrahedralColorMapper() override = default;

  void RenderPieceDraw(vtkRenderer* ren, vtkActor* act) override;
  void ComputeBounds() override;
  /// The superclass's, with this mapper's own VBO cache in place of the
  /// context's: VTK 9.1 finds the entry of a released VBO by scanning every
  /// array its cache holds (vtkOpenGLVertexBufferObjectCache::RemoveVBO), so
  /// with one mapper per chunk in the context's cache, releasing n chunks cost
  /// n^2 steps (dropping 30,000 chunk actors stalled the editor for minutes).
  /// A chunk's arrays belong to it alone: nothing is lost by not sharing them.
  void BuildBufferObjects(vtkRenderer* ren, vtkActor* act) override;

  int InterpolationMode = Tetrahedral;
  bool UsedTetrahedral = false;
  bool Matcap = false;
  int DrawRangeTriangles = 32;
  int DrawRangePad = 1;
  vtkIdType LastTrianglesDrawn = 0;
  int LastDrawCalls = 0;
  vtkTimeStamp DrawTime;
  vtkSmartPointer<vtkOpenGLVertexBufferObjectCache> OwnVBOCache;

private:
  // SetInputBounds: the bounds, and the input and times they hold for
  double InputBounds[6];
  vtkPolyData* InputBoundsData = nullptr; // compared, never dereferenced
  vtkMTimeType InputBoundsTime = 0, InputBoundsMeshTime = 0;

  /// Rebuilds Ranges when the buffers were rebuilt; false if the input does not qualify.
  bool UpdateDrawRanges();

  struct Range
  {
    vtkIdType First = 0, Count = 0;          // triangles
    unsigned int MinIndex = 0, MaxIndex = 0; // point ids they use
    double Box[6];
  };
  std::vector<Range> Ranges;
  bool RangesValid = false;
  vtkMTimeType RangesBuildTime = 0; // VBOBuildTime the ranges were made for
  int RangesTriangles = 0;          // DrawRangeTriangles they were made with

  vtkTetrahedralColorMapper(const vtkTetrahedralColorMapper&) = delete;
  void operator=(const vtkTetrahedralColorMapper&) = delete;
};

#endif
