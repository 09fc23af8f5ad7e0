// api/src/verify_stock.hpp: verify's stock left over the part's surface, and its map
// (docs/guide/verify.md, "Stock left").
#pragma once
#include <nlohmann/json.hpp>
#include <qmotion/api/verify.hpp>
#include <qmotion/cam/stock.hpp>
#include <string>

namespace qmotion::detail {

/// Cells of the part's surface the search may evaluate, on top of the part's triangles: in
/// all, and while it narrows the mean (the largest is settled first).
inline constexpr std::size_t kStockCells = std::size_t(1) << 19;
inline constexpr std::size_t kStockMeanCells = std::size_t(1) << 17;

/// The stock left on the part by the cutter over the program: branch and bound over the
/// part's triangles split in four, each cell's value at its centre within tol / 4 and the
/// value 1-Lipschitz over the cell, until the largest is within tol and the mean within tol
/// or the cells run out; then the value at every vertex of the part's mesh.
StockLeft stock_left(const cam::Program& program, const cam::CutIndex& cut, const sweep::Body& part,
                     const cam::Stock& stock, double tol);

nlohmann::json stock_json(const StockLeft& s);

/// The part coloured by the stock left (blue, darker where thicker), on size within tol
/// (white) and gouged (red): a .ply with vertex colours, or a view from above as .svg or
/// .png with its scale.
void write_stock_map(const std::string& path, const sweep::Body& part, const StockLeft& s,
                     double tol);

}  // namespace qmotion::detail
