// cyclone-accuracy's report: the summary page's "which setting to pick" table.
#pragma once

#include <ostream>
#include <vector>

#include "accuracy.h"

namespace cyclone::accuracy {

/// Which setting to pick for what, with the figures that say why, from `rows`.
void writeSummary(std::ostream &md, const std::vector<Row> &rows);

}  // namespace cyclone::accuracy
