// A DOF order that narrows the band of a pencil's pattern, for the band LU of
// inverse iteration. Models exported from other packages number their DOFs by
// node with the axial and torsional ones among the lateral ones (ROSS: 6 per
// node, 10 off-diagonals where the lateral ones alone need 7), or by kind (every
// x, then every y: a band of half the model). Reverse Cuthill-McKee on the union
// of the patterns; the given order is kept where it is as narrow.
#pragma once

#include <Eigen/Sparse>

#include <memory>
#include <mutex>
#include <vector>

namespace gyrokit {

struct BandOrder {
    std::vector<int> old_of;   // old_of[new index] = index in the given order
    std::vector<int> new_of;   // new_of[old index] = new index
};

using PatternList = std::vector<const Eigen::SparseMatrix<double>*>;

// Lower and upper bandwidth of the union of the patterns (square matrices of one
// size), in `order` (null: as given).
void pattern_bandwidths(const PatternList& matrices, const BandOrder* order, int& kl, int& ku);

// The reverse Cuthill-McKee order of the union of the patterns, or null where it
// does not narrow the band (kl + ku) of the given order.
std::shared_ptr<const BandOrder> narrower_band_order(const PatternList& matrices);

// The order of a system's pencils, found once: their pattern does not change with
// speed. Found again where the size or the count of entries differs from the
// pencil it was found for; a copy starts empty (a copied system may be edited).
// Any order gives the same solutions (the LU measures the band it gets), so a
// stale one could only cost time.
class BandOrderCache {
public:
    BandOrderCache() = default;
    BandOrderCache(const BandOrderCache&) {}
    BandOrderCache& operator=(const BandOrderCache&) {
        const std::lock_guard<std::mutex> lock(mutex_);
        found_ = false;
        order_.reset();
        return *this;
    }
    std::shared_ptr<const BandOrder> get(const PatternList& matrices);

private:
    std::mutex mutex_;
    bool found_ = false;
    std::vector<long> key_;
    std::shared_ptr<const BandOrder> order_;
};

}  // namespace gyrokit
