#include "vtkXMLSparseVolumeReader.h"

#include <vtkObjectFactory.h>

vtkStandardNewMacro(vtkXMLSparseVolumeReader);

const char* vtkXMLSparseVolumeReader::GetDataSetName()
{
  return "vtkSparseDictionaryVolume"; // vtkSparseDictionaryVolume's GetClassName(), which the writer writes
}

void vtkXMLSparseVolumeReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
