// Matcap images for the "Matcap (clay)" shading: the one the editor draws at
// start, and the conversion of any image (the user's own PNG or JPG) into the
// texture vtkChunkActorManager::SetMatcapTexture takes.
#pragma once

#include <QImage>

#include "vtkSmartPointer.h"

class vtkTexture;

/// A clay matcap of size x size pixels, computed here (no image file): the
/// picture of a matte, slightly warm sphere under a soft key light from the
/// upper left, a dim fill from the right and a faint rim. Pixel (x, y) shows
/// the normal (2x/size - 1, 1 - 2y/size, sqrt(1 - x'^2 - y'^2)); outside the
/// disc the rim's colour continues.
QImage makeClayMatcap(int size = 256);

/// The image as an RGB texture whose (u, v) = (0, 0) is the image's lower left
/// corner (rows flipped: Qt's first row is the top), interpolated, clamped.
vtkSmartPointer<vtkTexture> matcapTexture(const QImage& image);
