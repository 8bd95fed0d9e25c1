#include "vtkPartialRedrawCuller.h"

#include "vtkActor.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMapper.h"
#include "vtkMath.h"
#include "vtkDataObject.h"
#include "vtkMatrix4x4.h"
#include "vtkPolyData.h"
#include "vtkObjectFactory.h"
#include "vtkProp.h"
#include "vtkPropCollection.h"
#include "vtkProperty.h"
#include "vtkRect.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTexture.h"
#include "vtkWeakPointer.h"
#include "lvdifProjectedRect.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

vtkStandardNewMacro(vtkPartialRedrawCuller);

namespace
{
// Window pixels, half-open: [x0, x1) x [y0, y1); empty when x0 >= x1 or y0 >= y1.
struct Rect
{
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x0 >= x1 || y0 >= y1; }
  long long area() const { return empty() ? 0 : static_cast<long long>(x1 - x0) * (y1 - y0); }
  void unite(const Rect& o)
  {
    if (o.empty())
    {
      return;
    }
    if (this->empty())
    {
      *this = o;
      return;
    }
    x0 = std::min(x0, o.x0);
    y0 = std::min(y0, o.y0);
    x1 = std::max(x1, o.x1);
    y1 = std::max(y1, o.y1);
  }
  bool meets(const Rect& o) const
  {
    return !empty() && !o.empty() && x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1;
  }
};

// Lines and points are drawn a little wider than the geometry's projection.
constexpr int Pad = 3;
// Triangles are not: their fragments lie in the pixels their projection
// meets, [floor(lo), ceil(hi) + 1) already; SurfaceMargin (1) adds one more
// pixel for the rounding of the GPU's single-precision transform.

// Whether the prop draws only filled polygons (an actor showing a poly data
// of polygons and strips as a surface, without edges or vertices): nothing of
// it is drawn wider than its projection.
bool surfaceOnly(vtkProp* p)
{
  auto* a = vtkActor::SafeDownCast(p);
  vtkProperty* prop = a ? a->GetProperty() : nullptr;
  vtkMapper* mapper = a ? a->GetMapper() : nullptr;
  // (a poly data mapper drawing its input's cells: not glyphs or splats, whose
  // bounds the mapper computes otherwise)
  if (!prop || !mapper || !mapper->IsA("vtkPolyDataMapper") || mapper->IsA("vtkPointGaussianMapper") ||
    prop->GetRepresentation() != VTK_SURFACE || prop->GetEdgeVisibility() || prop->GetVertexVisibility() ||
    mapper->GetNumberOfInputConnections(0) == 0)
  {
    return false;
  }
  auto* pd = vtkPolyData::SafeDownCast(mapper->GetInputDataObject(0, 0));
  return pd && pd->GetNumberOfVerts() == 0 && pd->GetNumberOfLines() == 0 &&
    pd->GetNumberOfPolys() + pd->GetNumberOfStrips() > 0;
}

std::uint64_t mix(std::uint64_t h, std::uint64_t v)
{
  // FNV-1a over the value's bytes
  for (int i = 0; i < 8; ++i)
  {
    h ^= (v >> (8 * i)) & 0xff;
    h *= 1099511628211ull;
  }
  return h;
}
} // namespace

struct vtkPartialRedrawCuller::Internals
{
  struct Drawn
  {
    Rect rect;
    std::uint64_t signature = 0;
  };
  vtkWeakPointer<vtkRenderer> Renderer;
  unsigned long StartObserver = 0;
  unsigned long FramesStarted = 0; // the renderer's StartEvents
  unsigned long FramesCulled = 0;  // FramesStarted at the last Cull
  bool Valid = false;              // the framebuffer holds the frame recorded below
  std::vector<double> ViewKey;
  std::unordered_map<vtkProp*, Drawn> Props;
  struct Declared
  {
    std::uint64_t first = 0;  // signature before the first BeginChange
    std::uint64_t after = 0;  // signature after the last EndChange
    bool chained = true;      // nothing changed between one EndChange and the next BeginChange
    bool open = false;        // BeginChange without EndChange yet
    double box[6] = { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
    std::vector<double> points; // of the declarations that gave points (their boxes are not in `box`)
  };
  std::unordered_map<vtkProp*, Declared> Changes;
  // SetInputChangesAnnounced actors: their input's MTime as last read.
  struct AnnouncedInput
  {
    vtkWeakPointer<vtkActor> Actor;   // null once the actor is gone (its address may be reused)
    vtkDataObject* Input = nullptr;   // the input it was read from
    vtkMTimeType MTime = 0;
    vtkMapper* Mapper = nullptr;      // the mapper Input was looked up from, at its MTime
    vtkMTimeType MapperMTime = 0;
    bool Stale = true;                // announced changed since: read again
  };
  std::unordered_map<vtkProp*, AnnouncedInput> Announced;
  vtkNew<vtkPropCollection> Actors; // scratch

  void Attach(vtkRenderer* ren)
  {
    this->Detach();
    this->Renderer = ren;
    vtkNew<vtkCallbackCommand> cb;
    cb->SetClientData(this);
    cb->SetCallback([](vtkObject*, unsigned long, void* cd, void*) { ++static_cast<Internals*>(cd)->FramesStarted; });
    this->StartObserver = ren->AddObserver(vtkCommand::StartEvent, cb);
    this->FramesStarted = 1; // this frame's StartEvent came before the observer
    this->FramesCulled = 0;
    this->Valid = false;
  }
  void Detach()
  {
    if (this->Renderer && this->StartObserver)
    {
      this->Renderer->RemoveObserver(this->StartObserver);
    }
    this->Renderer = nullptr;
    this->StartObserver = 0;
    this->Valid = false;
    this->Props.clear();
  }

  // Everything outside the props that decides the picture: window, viewport,
  // camera matrices, renderer settings and lights.
  std::vector<double> MakeViewKey(vtkRenderer* ren)
  {
    std::vector<double> k;
    vtkRenderWindow* win = ren->GetRenderWindow();
    k.push_back(static_cast<double>(reinterpret_cast<std::uintptr_t>(win)));
    const int* size = win->GetSize();
    k.push_back(size[0]);
    k.push_back(size[1]);
    double tile[4];
    win->GetTileViewport(tile);
    k.insert(k.end(), tile, tile + 4);
    const double* vp = ren->GetViewport();
    k.insert(k.end(), vp, vp + 4);
    int w = 0, h = 0, x = 0, y = 0;
    ren->GetTiledSizeAndOrigin(&w, &h, &x, &y);
    k.insert(k.end(), { double(w), double(h), double(x), double(y) });
    vtkCamera* cam = ren->GetActiveCamera();
    vtkMatrix4x4* m = cam->GetCompositeProjectionTransformMatrix(ren->GetTiledAspectRatio(), -1, 1);
    k.insert(k.end(), &m->Element[0][0], &m->Element[0][0] + 16);
    m = cam->GetViewTransformMatrix();
    k.insert(k.end(), &m->Element[0][0], &m->Element[0][0] + 16);
    // the renderer's own settings (its GetMTime includes the camera's, which
    // the one-shot scissor below modifies)
    k.push_back(static_cast<double>(ren->vtkObject::GetMTime()));
    vtkLightCollection* lights = ren->GetLights();
    vtkCollectionSimpleIterator it;
    lights->InitTraversal(it);
    while (vtkLight* l = lights->GetNextLight(it))
    {
      k.push_back(static_cast<double>(l->GetMTime()));
    }
    return k;
  }

  // The record of an announced actor that is still alive, or null.
  AnnouncedInput* FindAnnounced(vtkProp* p)
  {
    auto it = this->Announced.find(p);
    return it != this->Announced.end() && it->second.Actor.Get() == p ? &it->second : nullptr;
  }

  // The MTime of a static mapper's input; for an announced actor the one
  // recorded at its last announcement (`reread`: read it now, as at an
  // announcement).
  vtkMTimeType InputMTime(vtkActor* a, vtkDataObject* input, bool reread)
  {
    AnnouncedInput* announced = this->FindAnnounced(a);
    if (!announced)
    {
      return input ? input->GetMTime() : 0;
    }
    AnnouncedInput& r = *announced;
    if (reread || r.Stale || r.Input != input)
    {
      r.Input = input;
      r.MTime = input ? input->GetMTime() : 0;
      r.Stale = false;
    }
    return r.MTime;
  }

  // A static mapper's input (the pipeline lookup costs more than the rest of
  // an actor's signature); an announced actor's as of its last announcement
  // or mapper change (its owner replaces the input only with an announcement).
  vtkDataObject* StaticInput(vtkActor* a, vtkMapper* mapper, bool reread)
  {
    AnnouncedInput* r = this->FindAnnounced(a);
    if (r && !reread && !r->Stale && r->Mapper == mapper && r->MapperMTime == mapper->GetMTime())
    {
      return r->Input;
    }
    vtkDataObject* input = mapper->GetNumberOfInputConnections(0) ? mapper->GetInputDataObject(0, 0) : nullptr;
    if (r)
    {
      r->Mapper = mapper;
      r->MapperMTime = mapper->GetMTime();
    }
    return input;
  }

  // One actor's part of a signature.
  std::uint64_t MixActor(std::uint64_t h, vtkActor* a, bool reread)
  {
    vtkMapper* mapper = a->GetMapper();
    if (mapper && mapper->GetStatic())
    {
      // a static mapper's input is up to date by contract: its redraw time
      // without the pipeline update that GetRedrawMTime makes
      vtkDataObject* input = this->StaticInput(a, mapper, reread);
      h = mix(h, reinterpret_cast<std::uintptr_t>(input));
      h = mix(h, std::max(mapper->GetMTime(), this->InputMTime(a, input, reread)));
    }
    else
    {
      h = mix(h, a->GetRedrawMTime());
    }
    h = mix(h, a->GetMTime());
    h = mix(h, a->GetVisibility());
    h = mix(h, a->GetProperty() ? a->GetProperty()->GetMTime() : 0);
    h = mix(h, a->GetBackfaceProperty() ? a->GetBackfaceProperty()->GetMTime() : 0);
    h = mix(h, a->GetTexture() ? a->GetTexture()->GetMTime() : 0);
    return h;
  }

  // What the prop draws depends on: its own and its actors' modification
  // times (an actor's includes its mapper and the mapper's input),
  // visibility, properties and textures. `reread`: announced inputs' MTimes
  // read now (at BeginChange and EndChange).
  std::uint64_t Signature(vtkProp* p, bool reread = false)
  {
    std::uint64_t h = 1469598103934665603ull;
    auto* actor = vtkActor::SafeDownCast(p);
    if (actor && this->FindAnnounced(p))
    {
      // an announced actor is a plain actor (its own only part): no
      // collection of its parts, per actor and frame
      return this->MixActor(mix(h, p->GetMTime()), actor, reread);
    }
    // An actor is its own only part (GetActors below), which covers its
    // redraw time; vtkActor::GetRedrawMTime would also update the mapper's
    // pipeline, per prop and frame, even for a static mapper.
    if (!actor)
    {
      h = mix(h, p->GetRedrawMTime());
    }
    h = mix(h, p->GetMTime());
    this->Actors->RemoveAllItems();
    p->GetActors(this->Actors);
    vtkCollectionSimpleIterator it;
    this->Actors->InitTraversal(it);
    while (vtkProp* q = this->Actors->GetNextProp(it))
    {
      if (auto* a = vtkActor::SafeDownCast(q))
      {
        h = this->MixActor(h, a, reread);
      }
      else
      {
        h = mix(h, q->GetRedrawMTime());
        h = mix(h, q->GetMTime());
        h = mix(h, q->GetVisibility());
      }
    }
    return h;
  }
};

vtkPartialRedrawCuller::vtkPartialRedrawCuller()
  : Internal(new Internals)
{
}

vtkPartialRedrawCuller::~vtkPartialRedrawCuller()
{
  this->Internal->Detach();
}

void vtkPartialRedrawCuller::BeginChange(vtkProp* prop)
{
  if (!this->Enabled || !prop)
  {
    return;
  }
  const std::uint64_t sig = this->Internal->Signature(prop, true);
  auto it = this->Internal->Changes.find(prop);
  if (it == this->Internal->Changes.end())
  {
    Internals::Declared d;
    d.first = sig;
    d.open = true;
    this->Internal->Changes.emplace(prop, d);
    return;
  }
  it->second.chained = it->second.chained && !it->second.open && sig == it->second.after;
  it->second.open = true;
}

void vtkPartialRedrawCuller::EndChange(vtkProp* prop, const double bounds[6])
{
  this->EndChange(prop, bounds, nullptr, 0);
}

void vtkPartialRedrawCuller::EndChange(
  vtkProp* prop, const double bounds[6], const double* points, vtkIdType numberOfPoints)
{
  auto it = prop ? this->Internal->Changes.find(prop) : this->Internal->Changes.end();
  if (it == this->Internal->Changes.end())
  {
    return;
  }
  Internals::Declared& d = it->second;
  d.chained = d.chained && d.open;
  d.open = false;
  d.after = this->Internal->Signature(prop, true);
  if (points && numberOfPoints > 0)
  {
    d.points.insert(d.points.end(), points, points + 3 * numberOfPoints);
    return;
  }
  if (bounds && vtkMath::AreBoundsInitialized(bounds) && bounds[0] <= bounds[1] && bounds[2] <= bounds[3] &&
    bounds[4] <= bounds[5])
  {
    for (int a = 0; a < 3; ++a)
    {
      d.box[2 * a] = std::min(d.box[2 * a], bounds[2 * a]);
      d.box[2 * a + 1] = std::max(d.box[2 * a + 1], bounds[2 * a + 1]);
    }
  }
}

void vtkPartialRedrawCuller::SetInputChangesAnnounced(vtkActor* actor, bool announced)
{
  if (!actor)
  {
    return;
  }
  if (!announced)
  {
    this->Internal->Announced.erase(actor);
    return;
  }
  Internals::AnnouncedInput& r = this->Internal->Announced[actor];
  r.Actor = actor;
  r.Stale = true;
}

void vtkPartialRedrawCuller::InputDataChanged(vtkActor* actor)
{
  auto it = actor ? this->Internal->Announced.find(actor) : this->Internal->Announced.end();
  if (it != this->Internal->Announced.end())
  {
    it->second.Stale = true;
  }
}

bool vtkPartialRedrawCuller::GetLastFramePartial(int damage[4])
{
  const Internals& in = *this->Internal;
  if (!this->Enabled || !this->LastPartial || !in.Renderer || in.FramesCulled != in.FramesStarted)
  {
    return false;
  }
  std::copy(this->LastDamage, this->LastDamage + 4, damage);
  return true;
}

void vtkPartialRedrawCuller::SetEnabled(bool enabled)
{
  if (enabled == this->Enabled)
  {
    return;
  }
  this->Enabled = enabled;
  this->Internal->Valid = false;
  this->Internal->Props.clear();
  this->Internal->Changes.clear();
  for (auto& kv : this->Internal->Announced)
  {
    kv.second.Stale = true; // changes made while disabled were not announced
  }
  this->Modified();
}

double vtkPartialRedrawCuller::Cull(vtkRenderer* ren, vtkProp** propList, int& listLength, int& initialized)
{
  Internals& in = *this->Internal;
  auto total = [&] {
    double t = 0;
    for (int i = 0; i < listLength; ++i)
    {
      t += initialized ? propList[i]->GetRenderTimeMultiplier() : 1.0;
    }
    return t;
  };
  if (!this->Enabled)
  {
    this->LastNumberOfPropsDrawn = listLength;
    return total();
  }
  if (ren != in.Renderer)
  {
    in.Attach(ren);
  }

  int vw = 0, vh = 0, vx = 0, vy = 0;
  ren->GetTiledSizeAndOrigin(&vw, &vh, &vx, &vy);
  const Rect viewport{ vx, vy, vx + vw, vy + vh };

  // Screen rectangles of this frame's props.
  vtkMatrix4x4* m = ren->GetActiveCamera()->GetCompositeProjectionTransformMatrix(ren->GetTiledAspectRatio(), -1, 1);
  const double* mm = &m->Element[0][0];
  const int vpi[4] = { vx, vy, vw, vh };
  // A projected rectangle (lvdifProjectedRect.h) clamped to the viewport; the
  // viewport when a point lies behind the eye (the projection does not bound it).
  auto clamped = [&](bool bounded, const double* p) {
    if (!bounded)
    {
      return viewport;
    }
    auto clampTo = [](double v, int a, int z) { return static_cast<int>(std::max<double>(a, std::min<double>(z, v))); };
    Rect r;
    r.x0 = clampTo(p[0], viewport.x0, viewport.x1);
    r.y0 = clampTo(p[1], viewport.y0, viewport.y1);
    r.x1 = clampTo(p[2], viewport.x0, viewport.x1);
    r.y1 = clampTo(p[3], viewport.y0, viewport.y1);
    return r;
  };
  // The rectangle of a box's 8 corners.
  auto boxRect = [&](const double* b, int pad) {
    if (!b)
    {
      return viewport; // 2D props and the like: assume everywhere
    }
    if (!vtkMath::AreBoundsInitialized(b) || b[0] > b[1] || b[2] > b[3] || b[4] > b[5])
    {
      return Rect{}; // draws nothing
    }
    double p[4];
    const bool bounded = lvdif::render::projectedBoxPixelRect(mm, vpi, b, pad, p);
    return clamped(bounded, p);
  };
  // The rectangle of projected points (x, y, z each).
  auto pointsRect = [&](const std::vector<double>& pts, int pad) {
    if (pts.empty())
    {
      return Rect{};
    }
    double p[4];
    const bool bounded = lvdif::render::projectedPixelRect(mm, vpi, pts.size() / 3, pad,
      [&pts](std::size_t i, double* x) {
        for (int a = 0; a < 3; ++a) x[a] = pts[3 * i + a];
      },
      p);
    return clamped(bounded, p);
  };
  const int surfacePad = this->SurfaceMargin;
  auto padOf = [surfacePad](vtkProp* p) { return surfaceOnly(p) ? surfacePad : Pad; };

  std::vector<double> key = in.MakeViewKey(ren);
  const bool sameView = in.Valid && key == in.ViewKey;
  std::unordered_map<vtkProp*, Internals::Drawn> now;
  now.reserve(static_cast<std::size_t>(listLength));
  Rect damage;
  for (int i = 0; i < listLength; ++i)
  {
    vtkProp* p = propList[i];
    Internals::Drawn d;
    d.signature = in.Signature(p);
    auto old = in.Props.find(p);
    // An actor of a static mapper whose signature and view are those of the
    // last frame has the same bounds, so the same rectangle: no bounds query
    // (which checks the input's modification times, per actor and frame).
    auto* actor = vtkActor::SafeDownCast(p);
    if (sameView && old != in.Props.end() && old->second.signature == d.signature && actor && actor->GetMapper() &&
      actor->GetMapper()->GetStatic())
    {
      d.rect = old->second.rect;
    }
    else
    {
      d.rect = boxRect(p->GetBounds(), padOf(p));
    }
    if (old == in.Props.end())
    {
      damage.unite(d.rect); // new, or shown again
    }
    else
    {
      auto declared = in.Changes.find(p);
      if (declared != in.Changes.end() && declared->second.chained && !declared->second.open &&
        declared->second.first == old->second.signature && declared->second.after == d.signature)
      {
        // only the declared boxes and points differ
        const int pad = padOf(p);
        damage.unite(boxRect(declared->second.box, pad));
        damage.unite(pointsRect(declared->second.points, pad));
      }
      else if (old->second.signature != d.signature ||
        !(old->second.rect.x0 == d.rect.x0 && old->second.rect.y0 == d.rect.y0 && old->second.rect.x1 == d.rect.x1 &&
          old->second.rect.y1 == d.rect.y1))
      {
        damage.unite(old->second.rect);
        damage.unite(d.rect);
      }
      in.Props.erase(old);
    }
    now.emplace(p, d);
  }
  for (const auto& gone : in.Props) // removed, hidden or culled since the last frame
  {
    damage.unite(gone.second.rect);
  }

  bool full = !in.Valid || this->FullRedrawRequested || key != in.ViewKey || ren->GetSelector() != nullptr ||
    in.FramesStarted != in.FramesCulled + 1 ||
    static_cast<double>(damage.area()) > this->MaximumDamageFraction * static_cast<double>(viewport.area());

  int kept = listLength;
  if (!full)
  {
    // Keep, in order, the props that cover the damage.
    std::vector<vtkProp*> drawn;
    for (int i = 0; i < listLength && !full; ++i)
    {
      if (now[propList[i]].rect.meets(damage))
      {
        drawn.push_back(propList[i]);
        full = propList[i]->HasTranslucentPolygonalGeometry() != 0; // blended passes read the whole frame
      }
    }
    if (!full)
    {
      kept = static_cast<int>(drawn.size());
      std::copy(drawn.begin(), drawn.end(), propList);
      vtkCamera* cam = ren->GetActiveCamera();
      cam->SetScissorRect(damage.empty()
          ? vtkRecti(viewport.x0, viewport.y0, 0, 0)
          : vtkRecti(damage.x0, damage.y0, damage.x1 - damage.x0, damage.y1 - damage.y0));
      cam->SetUseScissor(true); // one-shot: vtkOpenGLCamera::Render clears and draws inside it
    }
  }

  // This frame, as it will be on screen: the next one is compared with it.
  in.Props.swap(now);
  in.Changes.clear();
  in.ViewKey.swap(key);
  in.Valid = ren->GetSelector() == nullptr; // a selection pass draws ids, not the picture
  in.FramesCulled = in.FramesStarted;
  this->FullRedrawRequested = false;
  this->LastPartial = !full;
  if (full)
  {
    ++this->NumberOfFullRedraws;
    this->LastDamage[0] = viewport.x0;
    this->LastDamage[1] = viewport.y0;
    this->LastDamage[2] = vw;
    this->LastDamage[3] = vh;
  }
  else
  {
    ++this->NumberOfPartialRedraws;
    this->LastDamage[0] = damage.x0;
    this->LastDamage[1] = damage.y0;
    this->LastDamage[2] = damage.empty() ? 0 : damage.x1 - damage.x0;
    this->LastDamage[3] = damage.empty() ? 0 : damage.y1 - damage.y0;
  }
  listLength = kept;
  this->LastNumberOfPropsDrawn = kept;
  return total();
}

void vtkPartialRedrawCuller::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Enabled: " << this->Enabled << "\n";
  os << indent << "MaximumDamageFraction: " << this->MaximumDamageFraction << "\n";
  os << indent << "SurfaceMargin: " << this->SurfaceMargin << "\n";
  os << indent << "NumberOfFullRedraws: " << this->NumberOfFullRedraws << "\n";
  os << indent << "NumberOfPartialRedraws: " << this->NumberOfPartialRedraws << "\n";
  os << indent << "LastNumberOfPropsDrawn: " << this->LastNumberOfPropsDrawn << "\n";
}
