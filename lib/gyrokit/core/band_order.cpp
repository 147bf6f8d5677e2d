#include <gyrokit/core/band_order.hpp>

#include <algorithm>

namespace gyrokit {

void pattern_bandwidths(const PatternList& matrices, const BandOrder* order, int& kl, int& ku) {
    kl = ku = 0;
    for (const Eigen::SparseMatrix<double>* A : matrices)
        for (Eigen::Index k = 0; k < A->outerSize(); ++k) {
            const int c = order ? order->new_of[static_cast<size_t>(k)] : static_cast<int>(k);
            for (Eigen::SparseMatrix<double>::InnerIterator it(*A, k); it; ++it) {
                const int r = order ? order->new_of[static_cast<size_t>(it.row())] : static_cast<int>(it.row());
                kl = std::max(kl, r - c);
                ku = std::max(ku, c - r);
            }
        }
}

namespace {

// Breadth-first levels from `start` over the nodes not yet `placed` (a component):
// the last level's node of least degree (first by index) and the level count.
std::pair<int, int> farthest(const std::vector<std::vector<int>>& adj, const std::vector<char>& placed, int start,
                             std::vector<int>& level) {
    std::vector<int> queue{start};
    level[static_cast<size_t>(start)] = 0;
    for (size_t q = 0; q < queue.size(); ++q)
        for (const int v : adj[static_cast<size_t>(queue[q])])
            if (!placed[static_cast<size_t>(v)] && level[static_cast<size_t>(v)] < 0) {
                level[static_cast<size_t>(v)] = level[static_cast<size_t>(queue[q])] + 1;
                queue.push_back(v);
            }
    const int depth = level[static_cast<size_t>(queue.back())];
    int best = queue.back();
    for (const int v : queue)
        if (level[static_cast<size_t>(v)] == depth &&
            (adj[static_cast<size_t>(v)].size() < adj[static_cast<size_t>(best)].size() ||
             (adj[static_cast<size_t>(v)].size() == adj[static_cast<size_t>(best)].size() && v < best)))
            best = v;
    for (const int v : queue) level[static_cast<size_t>(v)] = -1;
    return {best, depth};
}

}  // namespace

std::shared_ptr<const BandOrder> narrower_band_order(const PatternList& matrices) {
    if (matrices.empty()) return nullptr;
    const int n = static_cast<int>(matrices.front()->rows());
    std::vector<std::vector<int>> adj(static_cast<size_t>(n));
    for (const Eigen::SparseMatrix<double>* A : matrices)
        for (Eigen::Index k = 0; k < A->outerSize(); ++k)
            for (Eigen::SparseMatrix<double>::InnerIterator it(*A, k); it; ++it)
                if (it.row() != k) {
                    adj[static_cast<size_t>(it.row())].push_back(static_cast<int>(k));
                    adj[static_cast<size_t>(k)].push_back(static_cast<int>(it.row()));
                }
    for (std::vector<int>& a : adj) {
        std::sort(a.begin(), a.end());
        a.erase(std::unique(a.begin(), a.end()), a.end());
    }
    // Neighbours in order of degree (then index): Cuthill-McKee's visiting order.
    for (std::vector<int>& a : adj)
        std::stable_sort(a.begin(), a.end(),
                         [&](int u, int v) { return adj[static_cast<size_t>(u)].size() < adj[static_cast<size_t>(v)].size(); });
    std::vector<char> placed(static_cast<size_t>(n), 0);
    std::vector<int> level(static_cast<size_t>(n), -1), order;
    order.reserve(static_cast<size_t>(n));
    for (int s = 0; s < n; ++s) {
        if (placed[static_cast<size_t>(s)]) continue;
        // A pseudo-peripheral start (George and Liu): move to the far end while the
        // component's depth grows.
        auto [start, depth] = farthest(adj, placed, s, level);
        for (int round = 0; round < 8; ++round) {
            const auto [next, d] = farthest(adj, placed, start, level);
            if (d <= depth) break;
            start = next, depth = d;
        }
        const size_t first = order.size();
        order.push_back(start);
        placed[static_cast<size_t>(start)] = 1;
        for (size_t q = first; q < order.size(); ++q)
            for (const int v : adj[static_cast<size_t>(order[q])])
                if (!placed[static_cast<size_t>(v)]) placed[static_cast<size_t>(v)] = 1, order.push_back(v);
    }
    auto result = std::make_shared<BandOrder>();
    result->old_of.assign(order.rbegin(), order.rend());
    result->new_of.resize(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) result->new_of[static_cast<size_t>(result->old_of[static_cast<size_t>(i)])] = i;
    int kl0 = 0, ku0 = 0, kl = 0, ku = 0;
    pattern_bandwidths(matrices, nullptr, kl0, ku0);
    pattern_bandwidths(matrices, result.get(), kl, ku);
    if (kl + ku >= kl0 + ku0) return nullptr;
    return result;
}

std::shared_ptr<const BandOrder> BandOrderCache::get(const PatternList& matrices) {
    std::vector<long> key;
    for (const Eigen::SparseMatrix<double>* A : matrices) key.push_back(static_cast<long>(A->rows())), key.push_back(static_cast<long>(A->nonZeros()));
    const std::lock_guard<std::mutex> lock(mutex_);
    if (!found_ || key != key_) {
        order_ = narrower_band_order(matrices);
        key_ = std::move(key);
        found_ = true;
    }
    return order_;
}

}  // namespace gyrokit
