#include "vtkTetrahedralColorMapper.h"

#include "vtkActor.h"
#include "vtkCornerColorAttributes.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkShaderProperty.h"

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
{
  this->SetColorModeToDirectScalars();
  this->SetScalarModeToUsePointFieldData();
  this->SelectColorArray("rgba");
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

void vtkTetrahedralColorMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "InterpolationMode: " << (this->InterpolationMode == Tetrahedral ? "Tetrahedral" : "PerVertex")
     << "\n";
  os << indent << "UsedTetrahedral: " << this->UsedTetrahedral << "\n";
  os << indent << "Matcap: " << this->Matcap << "\n";
}
