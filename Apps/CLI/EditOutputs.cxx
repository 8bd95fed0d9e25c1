#include "EditOutputs.h"

#include "Commands.h"

#include "MeshOutput.h"
#include "VolumeFiles.h"

#include "vtkPolyData.h"

#include <cstdio>

void CheckEditOutputs(const Arguments& args)
{
  if (args.has("out"))
    CheckVolumeOutput(args.get("out", ""));
  if (args.has("mesh"))
    CheckMeshOutput(args.get("mesh", ""));
  if (args.has("png"))
    CheckPngOutput(args.get("png", ""));
}

void AcceptEditCommandLine(const Arguments& args)
{
  CommandLineAccepted();
  if (args.has("png"))
    RequireDisplay(args.get("png", ""));
}

void WriteEditOutputs(const lvdif::DictionaryVolume& volume, const Arguments& args,
  const std::map<std::string, std::string>& metadata, lvdif::Interrupter& progress)
{
  if (args.has("out"))
  {
    SaveAnyVolume(volume, args.get("out", ""), metadata, progress);
    std::printf("volume -> %s\n", args.get("out", "").c_str());
  }
  if (args.has("mesh") || args.has("png"))
  {
    vtkSmartPointer<vtkPolyData> mesh = MeshVolume(volume, progress);
    if (args.has("mesh"))
    {
      WriteMesh(mesh, args.get("mesh", ""));
      std::printf("mesh (%lld triangles) -> %s\n", (long long)mesh->GetNumberOfPolys(), args.get("mesh", "").c_str());
    }
    if (args.has("png"))
    {
      RenderPng(mesh, args.get("png", ""));
      std::printf("picture -> %s\n", args.get("png", "").c_str());
    }
  }
}
