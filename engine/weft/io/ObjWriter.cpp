#include <weft/io/ObjWriter.h>

#include <weft/core/Error.h>

#include <cstdio>
#include <memory>

namespace weft {

void writeObj(const std::string& path, const TriangleMesh& mesh,
              const std::vector<std::pair<std::string, int>>& groupStarts) {
  std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "w"), &std::fclose);
  if (!f) throw InputError(path, "output", "cannot open for writing");
  std::fprintf(f.get(), "# written by weft\n");
  for (int i = 0; i < mesh.vertexCount(); ++i)
    std::fprintf(f.get(), "v %.17g %.17g %.17g\n", mesh.vertices(i, 0), mesh.vertices(i, 1),
                 mesh.vertices(i, 2));
  std::size_t group = 0;
  for (int t = 0; t < mesh.triangleCount(); ++t) {
    while (group < groupStarts.size() && groupStarts[group].second == t)
      std::fprintf(f.get(), "o %s\n", groupStarts[group++].first.c_str());
    std::fprintf(f.get(), "f %d %d %d\n", mesh.triangles(t, 0) + 1, mesh.triangles(t, 1) + 1,
                 mesh.triangles(t, 2) + 1);
  }
  if (std::ferror(f.get())) throw InputError(path, "output", "write failed");
}

}  // namespace weft
