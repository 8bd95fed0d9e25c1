// The data layouts of the CUDA mesh to SDF path, shared by the device copy of
// the mesh (MeshToSdfCudaMesh.cu) and the sessions' kernels
// (MeshToSdfCudaKernels.cuh, MeshToSdfCudaFar.cuh, MeshToSdfCudaDipole.cuh):
// the BVH nodes as the host builds them, leaf-ordered triangle copies, the
// winding structures and the correction's dipole tree.
#pragma once

#include "MeshToSdfDipoleDecide.h"
#include "MeshToSdfInternal.h"

namespace lvdif
{
namespace detail::meshtosdf_cuda
{

using namespace detail::meshtosdf;

struct GpuNode
{
  double lo[3], hi[3];
  int left, right, first, count;
};

using GpuTri = LeafTri; // vertices and unit normal, in BVH leaf order

struct DevBvh
{
  // by triangle index, mesh BVH of Normal/PseudoNormal sessions only: the records,
  // their pseudo-normals, the mesh's vertex normals at their corners (null if none)
  const Tri* tris = nullptr;
  const TriNormals* normals = nullptr;
  const CornerNormals* corners = nullptr;
  const GpuTri* leaf = nullptr; // leaf[i] = triangle order[i]
  const GpuNode* nodes = nullptr;
  const int* order = nullptr;
};

struct WindingDev
{
  DevBvh closed;      // tris unused (null): leaf records only
  int meshTris = 0;                 // closed triangles [0, meshTris) are the mesh's (crossings of the rest: caps or cone)
  int allTris = 0;                  // triangles of M as given (the all-solid-angle fallback)
  const GpuTri* meshLeaf = nullptr; // the mesh BVH's leaves and the slot of each triangle there:
  const int* meshSlot = nullptr;    // the mesh in index order, for the all-solid-angle fallback
  const GpuTri* cone = nullptr;
  int coneCount = 0;
  const WindingSigner::Cluster* clusters = nullptr;
  int clusterCount = 0;
};

using DipoleNode = DipoleTree::Node;
using DipoleDev = DipoleView;

} // namespace detail::meshtosdf_cuda
} // namespace lvdif
