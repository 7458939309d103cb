// Opening a PostGIS source for reading (private to fdr_gis; vector_input.cpp).
#pragma once
#include <string>

#include "gis/gdal_util.hpp"
#include "gis/pg_source.hpp"

class OGRLayer;

namespace fdr::gis {

// The database of a "PG:..." connection string, read-only through GDAL's PostgreSQL driver;
// kInputUnreadable "<connection without password>: cannot connect: <server's reason>" when the
// server refuses (wrong password, no such database, no server on that socket or host).
DatasetPtr open_pg_vector(const std::string& conn);

// Refuses a table or view without a geometry column (kInputUnreadable naming it): the PG driver
// opens such a table as a layer whose features carry no geometry.
void check_pg_layer(OGRLayer& layer, const std::string& conn);

}  // namespace fdr::gis
