/**
 * @class   vtkXMLSparseVolumeReader
 * @brief   Reads the .vtpd that VTK's XML partitioned-dataset writer makes of a
 *          vtkSparseDictionaryVolume (ParaView's Save Data as .vtpd).
 *
 * vtkXMLCompositeDataWriter names the index file's element after its input's
 * class, so a sparse volume saved as .vtpd holds a `vtkSparseDictionaryVolume`
 * element, which vtkXMLPartitionedDataSetReader refuses ("Cannot find
 * vtkPartitionedDataSet element"). This reader reads that element the same way:
 * the output is a plain vtkPartitionedDataSet of the saved partitions (one image
 * per storage chunk of the band, as in memory), not a sparse volume again.
 * CanReadFile answers yes only for such files, so ParaView's Open takes it for
 * exactly those and VTK's own reader for every other .vtpd.
 */
#ifndef vtkXMLSparseVolumeReader_h
#define vtkXMLSparseVolumeReader_h

#include "lvdifIOVolumeModule.h"

#include <vtkXMLPartitionedDataSetReader.h>

class LVDIFIOVOLUME_EXPORT vtkXMLSparseVolumeReader : public vtkXMLPartitionedDataSetReader
{
public:
  static vtkXMLSparseVolumeReader* New();
  vtkTypeMacro(vtkXMLSparseVolumeReader, vtkXMLPartitionedDataSetReader);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkXMLSparseVolumeReader() = default;
  ~vtkXMLSparseVolumeReader() override = default;

  /// The element (and file type) the writer names after the sparse volume's class.
  const char* GetDataSetName() override;

private:
  vtkXMLSparseVolumeReader(const vtkXMLSparseVolumeReader&) = delete;
  void operator=(const vtkXMLSparseVolumeReader&) = delete;
};

#endif
