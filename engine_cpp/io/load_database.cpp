// loadDatabase: the readers and checks in order (io/readers.hpp).
#include "io/readers.hpp"

#include "io/validate.hpp"

namespace xroute {

Database loadDatabase(const std::vector<std::string>& lefPaths, const std::string& defPath,
                      const std::string& guidePath) {
  Database db;
  db.lefPaths = lefPaths;
  db.guidePath = guidePath;
  for (const std::string& lef : lefPaths) readLef(lef, db.tech);
  validateTech(db.tech, lefPaths);
  readDef(defPath, db.tech, db.design);
  validateDesign(db.tech, db.design, defPath);
  if (!guidePath.empty()) readGuides(guidePath, db.tech, db.design);
  return db;
}

}  // namespace xroute
