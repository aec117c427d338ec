// SPDX-License-Identifier: MIT
// matrix_market.h — write a RenderingMatrix in Matrix Market text format (coordinate real
// general for A, array real general for vectors), 17 significant digits so doubles round-trip.
// Files are written to a temporary name and renamed, so a failure leaves no partial output.
#pragma once

#include <string>
#include <vector>

#include "raster/render.h"

namespace pem::cli {

void WriteMatrixMarket(const std::string& path, const raster::RenderingMatrix& a);
void WriteVectorMarket(const std::string& path, const std::vector<double>& v,
                       const std::string& comment);

}  // namespace pem::cli
