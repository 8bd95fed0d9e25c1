#include "vtkTetrahedralColorMapper.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCornerColorAttributes.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLHelper.h"
#include "vtkOpenGLIndexBufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkOpenGLVertexBufferObjectCache.h"
#include "vtkOpenGLVertexBufferObjectGroup.h"
#include "vtkPoints.h"
#include "vtkRenderer.h"
#include "vtk_glew.h"
#include "lvdifProjectedRect.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkShaderProperty.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

vtkStandardNewMacro(vtkTetrahedralColorMapper);

namespace
{
// Shader fragments. Attribute names are those of the mapped arrays' shader
// side; VTK uploads extra vertex attributes as floats without normalising,
// so the colours arrive in 0..255.
const char* const VsDec = R"(//VTK::Normal::Dec
in vec3 lvdifLocal;
in vec4 lvdifP0; in vec4 lvdifP1; in vec4 lvdifP2;
out vec3 lvdifLocalVS;
flat out vec4 lvdifPV0; flat out vec4 lvdifPV1; flat out vec4 lvdifPV2;
)";

const char* const VsImpl = R"(//VTK::Normal::Impl
  lvdifLocalVS = lvdifLocal;
  lvdifPV0 = lvdifP0; lvdifPV1 = lvdifP1; lvdifPV2 = lvdifP2;
)";

// Corner c = x + 2y + 4z: C0=c000 C1=c100 C2=c010 C3=c110 C4=c001 C5=c101 C6=c011 C7=c111.
// The six tetrahedra share the diagonal c000-c111; the order of x, y, z
// picks one, and the weights are the differences of the sorted coordinates.
// The corner colours arrive packed (vtkCornerColorAttributes::PackCorners:
// byte i at float i/3, times 256^(i%3)); integers below 2^24, so the
// divisions by powers of two, floor and the differences are exact.
const char* const FsDec = R"(//VTK::Normal::Dec
in vec3 lvdifLocalVS;
flat in vec4 lvdifPV0; flat in vec4 lvdifPV1; flat in vec4 lvdifPV2;
vec4 lvdifTetrahedral(vec3 u)
{
  float lvdifP[12] = float[12](lvdifPV0.x, lvdifPV0.y, lvdifPV0.z, lvdifPV0.w, lvdifPV1.x, lvdifPV1.y,
    lvdifPV1.z, lvdifPV1.w, lvdifPV2.x, lvdifPV2.y, lvdifPV2.z, lvdifPV2.w);
  float lvdifB[36];
  for (int j = 0; j < 12; ++j)
  {
    float v = lvdifP[j];
    float hi = floor(v / 65536.0);
    float rest = v - hi * 65536.0;
    float mid = floor(rest / 256.0);
    lvdifB[3 * j] = rest - mid * 256.0;
    lvdifB[3 * j + 1] = mid;
    lvdifB[3 * j + 2] = hi;
  }
  vec4 lvdifCV0 = vec4(lvdifB[0], lvdifB[1], lvdifB[2], lvdifB[3]);
  vec4 lvdifCV1 = vec4(lvdifB[4], lvdifB[5], lvdifB[6], lvdifB[7]);
  vec4 lvdifCV2 = vec4(lvdifB[8], lvdifB[9], lvdifB[10], lvdifB[11]);
  vec4 lvdifCV3 = vec4(lvdifB[12], lvdifB[13], lvdifB[14], lvdifB[15]);
  vec4 lvdifCV4 = vec4(lvdifB[16], lvdifB[17], lvdifB[18], lvdifB[19]);
  vec4 lvdifCV5 = vec4(lvdifB[20], lvdifB[21], lvdifB[22], lvdifB[23]);
  vec4 lvdifCV6 = vec4(lvdifB[24], lvdifB[25], lvdifB[26], lvdifB[27]);
  vec4 lvdifCV7 = vec4(lvdifB[28], lvdifB[29], lvdifB[30], lvdifB[31]);
  u = clamp(u, 0.0, 1.0);
  float x = u.x, y = u.y, z = u.z;
  vec4 c;
  if (x >= y)
  {
    if (y >= z)      { c = (1.0-x)*lvdifCV0 + (x-y)*lvdifCV1 + (y-z)*lvdifCV3 + z*lvdifCV7; }
    else if (x >= z) { c = (1.0-x)*lvdifCV0 + (x-z)*lvdifCV1 + (z-y)*lvdifCV5 + y*lvdifCV7; }
    else             { c = (1.0-z)*lvdifCV0 + (z-x)*lvdifCV4 + (x-y)*lvdifCV5 + y*lvdifCV7; }
  }
  else
  {
    if (z >= y)      { c = (1.0-z)*lvdifCV0 + (z-y)*lvdifCV4 + (y-x)*lvdifCV6 + x*lvdifCV7; }
    else if (z >= x) { c = (1.0-y)*lvdifCV0 + (y-z)*lvdifCV2 + (z-x)*lvdifCV6 + x*lvdifCV7; }
    else             { c = (1.0-y)*lvdifCV0 + (y-x)*lvdifCV2 + (x-z)*lvdifCV3 + z*lvdifCV7; }
  }
  return c * (1.0 / 255.0);
}
)";

const char* const FsImpl = R"(//VTK::Color::Impl
  {
    vec4 lvdifColor = lvdifTetrahedral(lvdifLocalVS);
    ambientColor = ambientIntensity * lvdifColor.rgb;
    diffuseColor = diffuseIntensity * lvdifColor.rgb;
    opacity = opacity * lvdifColor.a;
  }
)";

// Matcap: after VTK's lighting (kept tag first), the fragment's colour is
// replaced by the image's colour at the view-space normal times the surface
// colour. VTK declares the property texture as `uniform sampler2D lvdifMatcap`
// (its name) and binds it; the mesh needs no texture coordinates.
const char* const FsMatcap = R"(//VTK::Light::Impl
  {
    vec3 lvdifN = normalize(normalVCVSOutput);
    vec2 lvdifUV = clamp(lvdifN.xy * 0.5 + 0.5, 0.0, 1.0);
    gl_FragData[0] = vec4(texture(lvdifMatcap, lvdifUV).rgb * diffuseColor, opacity);
  }
)";

// Whether the property holds a replacement of this tag (each tag checked
// here is replaced in the fragment shader only).
bool hasReplacement(vtkShaderProperty* property, const char* tag)
{
  for (int i = 0; i < property->GetNumberOfShaderReplacements(); ++i)
  {
    std::string name, value;
    bool first = false, all = false;
    property->GetNthShaderReplacement(i, name, first, value, all);
    if (name == tag)
    {
      return true;
    }
  }
  return false;
}

bool hasTetrahedralArrays(vtkPolyData* pd)
{
  if (!pd || !pd->GetPointData()->GetArray(vtkCornerColorAttributes::LocalArrayName()))
  {
    return false;
  }
  for (int c = 0; c < 3; ++c)
  {
    if (!pd->GetPointData()->GetArray(vtkCornerColorAttributes::PackedCornerArrayName(c)))
    {
      return false;
    }
  }
  return true;
}
} // namespace

vtkTetrahedralColorMapper::vtkTetrahedralColorMapper()
  : OwnVBOCache(vtkSmartPointer<vtkOpenGLVertexBufferObjectCache>::New())
{
  this->SetColorModeToDirectScalars();
  this->SetScalarModeToUsePointFieldData();
  this->SelectColorArray("rgba");
}

vtkOpenGLVertexBufferObjectCache* vtkTetrahedralColorMapper::GetOwnVBOCache()
{
  return this->OwnVBOCache;
}

void vtkTetrahedralColorMapper::BuildBufferObjects(vtkRenderer* ren, vtkActor* act)
{
  // The superclass caches each array through the render window's cache, the
  // context's (vtkOpenGLState's): this mapper's own stands there meanwhile.
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow());
  vtkOpenGLState* state = window ? window->GetState() : nullptr;
  if (!state)
  {
    this->Superclass::BuildBufferObjects(ren, act);
    return;
  }
  vtkSmartPointer<vtkOpenGLVertexBufferObjectCache> shared = state->GetVBOCache();
  state->SetVBOCache(this->OwnVBOCache);
  this->Superclass::BuildBufferObjects(ren, act);
  state->SetVBOCache(shared);
}

void vtkTetrahedralColorMapper::InstallShaderReplacements(vtkShaderProperty* property, bool on)
{
  // Removing and re-adding would bump the property's MTime and rebuild the
  // shader every frame, so only act on a change of state.
  const bool installed = hasReplacement(property, "//VTK::Color::Impl");
  if (on == installed)
  {
    return;
  }
  if (!on)
  {
    property->ClearVertexShaderReplacement("//VTK::Normal::Dec", true);
    property->ClearVertexShaderReplacement("//VTK::Normal::Impl", true);
    property->ClearFragmentShaderReplacement("//VTK::Normal::Dec", true);
    property->ClearFragmentShaderReplacement("//VTK::Color::Impl", true);
    return;
  }
  property->AddVertexShaderReplacement("//VTK::Normal::Dec", true, VsDec, false);
  property->AddVertexShaderReplacement("//VTK::Normal::Impl", true, VsImpl, false);
  property->AddFragmentShaderReplacement("//VTK::Normal::Dec", true, FsDec, false);
  property->AddFragmentShaderReplacement("//VTK::Color::Impl", true, FsImpl, false);
}

void vtkTetrahedralColorMapper::InstallMatcapReplacement(vtkShaderProperty* property, bool on)
{
  if (on == hasReplacement(property, "//VTK::Light::Impl"))
  {
    return; // unchanged: keep the property's MTime (no shader rebuild)
  }
  if (on)
  {
    property->AddFragmentShaderReplacement("//VTK::Light::Impl", true, FsMatcap, false);
  }
  else
  {
    property->ClearFragmentShaderReplacement("//VTK::Light::Impl", true);
  }
}

void vtkTetrahedralColorMapper::RenderPiece(vtkRenderer* ren, vtkActor* act)
{
  const bool tetra = this->InterpolationMode == Tetrahedral && hasTetrahedralArrays(this->GetInput());
  if (tetra != this->UsedTetrahedral || this->ExtraAttributes.empty() == tetra)
  {
    this->RemoveAllVertexAttributeMappings();
    if (tetra)
    {
      static const char* shaderNames[3] = { "lvdifP0", "lvdifP1", "lvdifP2" };
      this->MapDataArrayToVertexAttribute(
        "lvdifLocal", vtkCornerColorAttributes::LocalArrayName(), vtkDataObject::FIELD_ASSOCIATION_POINTS, -1);
      for (int c = 0; c < 3; ++c)
      {
        this->MapDataArrayToVertexAttribute(shaderNames[c], vtkCornerColorAttributes::PackedCornerArrayName(c),
          vtkDataObject::FIELD_ASSOCIATION_POINTS, -1);
      }
    }
    this->SetScalarVisibility(!tetra);
    this->UsedTetrahedral = tetra;
  }
  InstallShaderReplacements(act->GetShaderProperty(), tetra);
  InstallMatcapReplacement(act->GetShaderProperty(),
    this->Matcap && act->GetProperty()->GetTexture(MatcapTextureName()) != nullptr);
  this->Superclass::RenderPiece(ren, act);
}

bool vtkTetrahedralColorMapper::UpdateDrawRanges()
{
  const vtkMTimeType built = this->VBOBuildTime.GetMTime();
  if (built == this->RangesBuildTime && this->RangesTriangles == this->DrawRangeTriangles)
  {
    return this->RangesValid;
  }
  this->RangesBuildTime = built;
  this->RangesTriangles = this->DrawRangeTriangles;
  this->RangesValid = false;
  this->Ranges.clear();
  vtkPolyData* pd = this->CurrentInput;
  const vtkIdType perRange = this->DrawRangeTriangles;
  if (!pd || perRange <= 0 || !pd->GetPoints() || pd->GetNumberOfVerts() || pd->GetNumberOfLines() ||
    pd->GetNumberOfStrips())
  {
    return false;
  }
  vtkCellArray* polys = pd->GetPolys();
  const vtkIdType n = polys->GetNumberOfCells();
  if (n == 0 || polys->GetNumberOfConnectivityIds() != 3 * n)
  {
    return false; // not only triangles
  }
  vtkPoints* pts = pd->GetPoints();
  const vtkIdType np = pts->GetNumberOfPoints();
  this->Ranges.reserve(static_cast<std::size_t>((n + perRange - 1) / perRange));
  vtkIdType npts = 0;
  const vtkIdType* ids = nullptr;
  vtkIdType t = 0; // triangles in the index buffer so far
  Range r;
  for (polys->InitTraversal(); polys->GetNextCell(npts, ids);)
  {
    double x[3][3];
    for (int v = 0; v < 3; ++v)
    {
      if (ids[v] < 0 || ids[v] >= np)
      {
        this->Ranges.clear();
        return false;
      }
      pts->GetPoint(ids[v], x[v]);
    }
    // VTK's index buffer leaves out the triangles with two equal points
    // (vtkOpenGLIndexBufferObject::AppendTriangleIndexBuffer): so do the ranges
    auto same = [&](int a, int b) { return x[a][0] == x[b][0] && x[a][1] == x[b][1] && x[a][2] == x[b][2]; };
    if (same(0, 1) || same(0, 2) || same(1, 2))
    {
      continue;
    }
    if (r.Count == 0)
    {
      r.First = t;
      r.MinIndex = ~0u;
      r.MaxIndex = 0;
      r.Box[0] = r.Box[2] = r.Box[4] = VTK_DOUBLE_MAX;
      r.Box[1] = r.Box[3] = r.Box[5] = -VTK_DOUBLE_MAX;
    }
    for (int v = 0; v < 3; ++v)
    {
      for (int a = 0; a < 3; ++a)
      {
        r.Box[2 * a] = std::min(r.Box[2 * a], x[v][a]);
        r.Box[2 * a + 1] = std::max(r.Box[2 * a + 1], x[v][a]);
      }
      r.MinIndex = std::min(r.MinIndex, static_cast<unsigned int>(ids[v]));
      r.MaxIndex = std::max(r.MaxIndex, static_cast<unsigned int>(ids[v]));
    }
    ++t;
    if (++r.Count == perRange)
    {
      this->Ranges.push_back(r);
      r.Count = 0;
    }
  }
  if (r.Count > 0)
  {
    this->Ranges.push_back(r);
  }
  // the ranges must cover the index buffer exactly, triangle for triangle
  if (this->Primitives[PrimitiveTris].IBO->IndexCount != static_cast<std::size_t>(3 * t))
  {
    this->Ranges.clear();
    return false;
  }
  this->RangesValid = !this->Ranges.empty();
  return this->RangesValid;
}

void vtkTetrahedralColorMapper::SetInputBounds(const double bounds[6])
{
  vtkPolyData* input = this->GetInput();
  this->InputBoundsData = input;
  if (!input)
  {
    return;
  }
  std::copy(bounds, bounds + 6, this->InputBounds);
  // the object's own time (a new points or cell array set) and its geometry's
  // (points and cells modified in place); vtkPolyData::GetMTime would also
  // visit every attribute array, which the bounds do not depend on
  this->InputBoundsTime = input->vtkObject::GetMTime();
  this->InputBoundsMeshTime = input->GetMeshMTime();
}

void vtkTetrahedralColorMapper::ComputeBounds()
{
  vtkPolyData* input = this->GetInput();
  if (input && input == this->InputBoundsData && input->vtkObject::GetMTime() == this->InputBoundsTime &&
    input->GetMeshMTime() == this->InputBoundsMeshTime)
  {
    std::copy(this->InputBounds, this->InputBounds + 6, this->Bounds);
    return;
  }
  this->Superclass::ComputeBounds();
}

void vtkTetrahedralColorMapper::RenderPieceDraw(vtkRenderer* ren, vtkActor* act)
{
  vtkOpenGLHelper& tris = this->Primitives[PrimitiveTris];
  const vtkIdType all = static_cast<vtkIdType>(tris.IBO->IndexCount / 3);
  this->LastTrianglesDrawn = all;
  this->LastDrawCalls = all ? 1 : 0;
  this->DrawTime.Modified();
  vtkProperty* prop = act->GetProperty();
  const bool plain = this->DrawRangeTriangles > 0 && !ren->GetSelector() && !this->GetSelection() &&
    prop->GetRepresentation() == VTK_SURFACE && !prop->GetEdgeVisibility() && !prop->GetVertexVisibility() &&
    !this->HaveCellScalars && !this->HaveCellNormals &&
    this->Primitives[PrimitivePoints].IBO->IndexCount == 0 && this->Primitives[PrimitiveLines].IBO->IndexCount == 0 &&
    this->Primitives[PrimitiveTriStrips].IBO->IndexCount == 0 && all > 0;
  if (!plain || !this->UpdateDrawRanges())
  {
    this->Superclass::RenderPieceDraw(ren, act);
    return;
  }

  // The region fragments may reach: the viewport, within the scissor box if the test is on.
  GLint vp[4] = { 0, 0, 0, 0 }, sb[4] = { 0, 0, 0, 0 };
  glGetIntegerv(GL_VIEWPORT, vp);
  int clip[4] = { vp[0], vp[1], vp[0] + vp[2], vp[1] + vp[3] }; // x0, y0, x1, y1 (half-open)
  if (glIsEnabled(GL_SCISSOR_TEST))
  {
    glGetIntegerv(GL_SCISSOR_BOX, sb);
    clip[0] = std::max(clip[0], static_cast<int>(sb[0]));
    clip[1] = std::max(clip[1], static_cast<int>(sb[1]));
    clip[2] = std::min(clip[2], static_cast<int>(sb[0] + sb[2]));
    clip[3] = std::min(clip[3], static_cast<int>(sb[1] + sb[3]));
  }

  // model to normalized device coordinates, as the camera and actor draw it
  vtkCamera* cam = ren->GetActiveCamera();
  vtkMatrix4x4* proj = cam->GetCompositeProjectionTransformMatrix(ren->GetTiledAspectRatio(), -1, 1);
  double m[16];
  if (act->GetIsIdentity())
  {
    std::copy(&proj->Element[0][0], &proj->Element[0][0] + 16, m);
  }
  else
  {
    vtkMatrix4x4::Multiply4x4(&proj->Element[0][0], &act->GetMatrix()->Element[0][0], m);
  }
  const int pad = this->DrawRangePad;
  const int viewport[4] = { vp[0], vp[1], vp[2], vp[3] };
  auto meets = [&](const Range& r) {
    if (clip[0] >= clip[2] || clip[1] >= clip[3])
    {
      return false; // no pixel can be written
    }
    double rect[4]; // the pixels the range may reach (lvdifProjectedRect.h)
    if (!lvdif::render::projectedBoxPixelRect(m, viewport, r.Box, pad, rect))
    {
      return true; // reaches behind the eye: the projection does not bound it
    }
    return rect[0] < clip[2] && clip[0] < rect[2] && rect[1] < clip[3] && clip[1] < rect[3];
  };

  // runs of consecutive ranges that meet it
  struct Run
  {
    vtkIdType First, Count;
    unsigned int MinIndex, MaxIndex;
  };
  std::vector<Run> runs;
  vtkIdType drawn = 0;
  bool open = false;
  for (const Range& r : this->Ranges)
  {
    if (!meets(r))
    {
      open = false;
      continue;
    }
    drawn += r.Count;
    if (open)
    {
      Run& last = runs.back();
      last.Count += r.Count;
      last.MinIndex = std::min(last.MinIndex, r.MinIndex);
      last.MaxIndex = std::max(last.MaxIndex, r.MaxIndex);
    }
    else
    {
      runs.push_back({ r.First, r.Count, r.MinIndex, r.MaxIndex });
      open = true;
    }
  }
  if (drawn == all)
  {
    this->Superclass::RenderPieceDraw(ren, act); // every triangle: VTK's own single draw
    return;
  }
  this->LastTrianglesDrawn = drawn;
  this->LastDrawCalls = static_cast<int>(runs.size());
  // as the base class draws the triangles, one call per run
  this->DrawingVertices = false;
  this->DrawingSelection = false;
  this->PointPicking = false;
  this->UpdateShaders(tris, ren, act);
  if (!runs.empty())
  {
    tris.IBO->Bind();
    for (const Run& run : runs)
    {
      glDrawRangeElements(GL_TRIANGLES, run.MinIndex, run.MaxIndex, static_cast<GLsizei>(3 * run.Count),
        GL_UNSIGNED_INT, reinterpret_cast<const GLvoid*>(static_cast<std::uintptr_t>(3 * run.First) * sizeof(GLuint)));
    }
    tris.IBO->Release();
  }
  this->PrimitiveIDOffset += static_cast<int>(all);
}

void vtkTetrahedralColorMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "InterpolationMode: " << (this->InterpolationMode == Tetrahedral ? "Tetrahedral" : "PerVertex")
     << "\n";
  os << indent << "UsedTetrahedral: " << this->UsedTetrahedral << "\n";
  os << indent << "Matcap: " << this->Matcap << "\n";
  os << indent << "DrawRangeTriangles: " << this->DrawRangeTriangles << "\n";
  os << indent << "DrawRangePad: " << this->DrawRangePad << "\n";
}
