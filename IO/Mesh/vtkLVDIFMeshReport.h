/**
 * @class   vtkLVDIFMeshReport
 * @brief   reports the health of a triangle mesh (OpenMesh) and optionally welds it
 *
 * Loads the input's polygons (polygons as triangle fans) into an OpenMesh
 * TriMesh and counts boundary edges, non-manifold edges and vertices, faces
 * OpenMesh's add_face refuses (complex edges), duplicated and degenerate faces
 * and connected components (definitions in LVDIFMeshCheck.h). The counts go
 * to the output's field data as one-tuple vtkIdTypeArrays (BoundaryEdges,
 * NonManifoldEdges, NonManifoldVertices, RefusedFaces, DuplicatedFaces,
 * DegenerateFaces, ConnectedComponents, WeldedVertices) plus a string array
 * MeshReport with the one-line summary, also available from GetSummary().
 * With Weld on, vertices closer than WeldTolerance are merged and the output
 * is the welded mesh (triangles, same face order, no normals); otherwise the
 * output is the input (shallow copy).
 */
#ifndef vtkLVDIFMeshReport_h
#define vtkLVDIFMeshReport_h

#include "lvdifIOMeshModule.h"
#include "vtkPolyDataAlgorithm.h"

#include <string>

class LVDIFIOMESH_EXPORT vtkLVDIFMeshReport : public vtkPolyDataAlgorithm
{
public:
  static vtkLVDIFMeshReport* New();
  vtkTypeMacro(vtkLVDIFMeshReport, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Merge vertices within WeldTolerance (world units) first (default off, 1e-6).
  /// With Weld on, a negative, NaN or infinite tolerance is an error at update (no clamp).
  vtkSetMacro(Weld, bool);
  vtkGetMacro(Weld, bool);
  vtkBooleanMacro(Weld, bool);
  vtkSetMacro(WeldTolerance, double);
  vtkGetMacro(WeldTolerance, double);
  ///@}

  /// The one-line summary of the last update ("" before).
  const char* GetSummary() const { return this->Summary.c_str(); }

protected:
  vtkLVDIFMeshReport();
  ~vtkLVDIFMeshReport() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  bool Weld = false;
  double WeldTolerance = 1e-6;
  std::string Summary;

private:
  vtkLVDIFMeshReport(const vtkLVDIFMeshReport&) = delete;
  void operator=(const vtkLVDIFMeshReport&) = delete;
};

#endif
