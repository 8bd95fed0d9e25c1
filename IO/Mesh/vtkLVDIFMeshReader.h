/**
 * @class   vtkLVDIFMeshReader
 * @brief   reads OBJ, OFF, STL and PLY triangle meshes with every index validated
 *
 * A thin wrapper over the core readers of lvdif/MeshFile.h (docs/FORMAT.md,
 * "Mesh files"): out-of-range or negative indices, faces of fewer than three
 * vertices, NaN or infinite coordinates, counts larger than the file and
 * files without triangles are one vtkErrorMacro naming the format, the line
 * or element and the problem, and an empty output (never a partly read mesh).
 * Polygons become triangle fans; STL corners are merged when bit-identical.
 * Output: vtkPolyData with float points, triangles and, when the file has
 * them, point normals.
 */
#ifndef vtkLVDIFMeshReader_h
#define vtkLVDIFMeshReader_h

#include "lvdifIOMeshModule.h"
#include "vtkPolyDataAlgorithm.h"

#include <string>

class LVDIFIOMESH_EXPORT vtkLVDIFMeshReader : public vtkPolyDataAlgorithm
{
public:
  static vtkLVDIFMeshReader* New();
  vtkTypeMacro(vtkLVDIFMeshReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);

  enum Formats
  {
    AUTO = 0, // from the extension
    OBJ,
    OFF,
    STL,
    PLY
  };
  ///@{
  /// The file format (default AUTO: from the file name's extension); anything
  /// but AUTO..PLY is an error at update (no clamp).
  vtkSetMacro(Format, int);
  vtkGetMacro(Format, int);
  ///@}

  /// True if the extension is one of .obj .off .stl .ply (any case).
  static bool CanReadFile(const char* fileName);

protected:
  vtkLVDIFMeshReader();
  ~vtkLVDIFMeshReader() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;
  int Format = AUTO;

private:
  vtkLVDIFMeshReader(const vtkLVDIFMeshReader&) = delete;
  void operator=(const vtkLVDIFMeshReader&) = delete;
};

#endif
