#include "PaperTables.h"

namespace weft::cli::paper {
namespace {

// Transcribed from DiffCloth (ACM TOG 2022) Tables 2, 3 and 4; ../shared/papers/diffcloth-li2022.txt.
const PublishedTaskFigures kPublished[] = {
    {"tshirt", "T-shirt", 6, 5, 6.62, {0.53, 0.60, 1.74}, {15.78, 2.43}, {4500, 53500, 47750},
     99.75, 4278, 250, "1/90", 141.5, 13.2},
    {"sphere_sysid", "Sphere", 1, 10, 0.46, {0.43, 0.00, 0.65}, {0.43, 2.37}, {2450, 18900, 11200},
     100.00, 1875, 350, "1/180", 5.1, 4.2},
    {"hat", "Hat", 18, 5, 21.83, {0.42, 0.55, 0.51}, {37.51, 5.87}, {11200, 159200, 106000}, 90.58,
     1737, 400, "1/100", 57.9, 20.7},
    {"sock", "Sock", 36, 5, 17.08, {11.59, 17.39, 18.43}, {64.70, 52.80}, {17600, 176800, 91600},
     99.41, 3165, 400, "1/160", 89.9, 14.3},
    {"dress", "Dress", 2, 16, 0.90, {76.91, 79.02, 77.25}, {80.02, 82.57}, {2750, 3125, 10000},
     84.80, 10902, 125, "1/120", 266.3, 84.7},
    {"flag", "Flag", 8, 10, 2.88, {4.77, 10.57, 25.57}, {38.89, 40.14}, {6800, 17300, 24800}, 96.00,
     1620, 100, "1/120", 13.7, 1.6},
};

}  // namespace

const PublishedTaskFigures* publishedFigures(const std::string& task) {
  for (const PublishedTaskFigures& f : kPublished)
    if (task == f.task) return &f;
  return nullptr;
}

}  // namespace weft::cli::paper
