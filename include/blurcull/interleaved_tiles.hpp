// blurcull's interleaved tile set, host only: the construction of the 81
// colour-cornered prototype tiles that the interleave method lays over the
// image (Aqsis 2.0 core, Fatahalian et al. 2009, Lagae and Dutre's corner
// tiles), and the cost it minimises. The per-sample part (the tuples, the
// corner colours, the jitter) is shared C++/GLSL text in patterns.hpp.
// docs/sampling.md explains the construction and its matching rule.
#pragma once

#include "patterns.hpp"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace blurcull {

struct InterleavedTileOptions {
    int width = 6;         // tiles of width x width lattice cells hold N = width^2 tuples (Aqsis: 6)
    int radius = 2;        // the greedy cost looks at a (2 radius + 1)^2 window
    double motion_weight = 0.5;  // q: 1 motion blur only, 0 defocus only, 0.5 both
    std::uint32_t seed = 1;
};

// 81 prototype tiles (3 corner colours, 3^4 corner combinations), each a
// permutation of the N tuples over its width x width cells. Lattice cell
// (gx, gy) lies in tile (gx / width, gy / width), whose prototype comes from
// the colours of its four lattice corners (patterns<Real>::interleaved_prototype).
struct InterleavedTiles {
    static constexpr int prototype_count = 81;
    int width = 0;
    int tuple_count = 0;  // N = width^2
    int radius = 0;
    double motion_weight = 0.5;
    std::uint32_t seed = 0;
    std::vector<glm::dvec3> tuples;          // (u, v, t) of tuple k: patternsd::interleaved_tuple(k)
    std::vector<std::uint16_t> slot_tuple;   // [prototype * N + cy * width + cx] -> tuple
    std::vector<std::uint16_t> tuple_slot;   // [prototype * N + tuple] -> cy * width + cx

    std::uint32_t prototype_of_tile(std::uint32_t tx, std::uint32_t ty) const {
        return patternsd::interleaved_prototype(tx, ty, seed);
    }
    // The tuple held by lattice cell (gx, gy).
    int tuple_at(std::uint32_t gx, std::uint32_t gy) const {
        const auto w = static_cast<std::uint32_t>(width);
        const std::uint32_t prototype = prototype_of_tile(gx / w, gy / w);
        return slot_tuple[static_cast<std::size_t>(prototype) * static_cast<std::size_t>(tuple_count) +
                          (gy % w) * w + gx % w];
    }
};

// The distance the tile optimisation spreads tuples by (Aqsis 2.0):
// d = sqrt(4 q dt^2 + (1 - q)(du^2 + dv^2)).
inline double interleaved_tuple_distance(const glm::dvec3& a, const glm::dvec3& b, double motion_weight) {
    const glm::dvec3 d = a - b;
    return std::sqrt(4.0 * motion_weight * d.z * d.z + (1.0 - motion_weight) * (d.x * d.x + d.y * d.y));
}

// Weight of the neighbour (i, j) cells away: exp(-0.7 (i^2 + j^2)).
inline double interleaved_neighbour_weight(int i, int j) { return std::exp(-0.7 * double(i * i + j * j)); }

// w / d for one pair, with d floored so that equal tuples side by side cost
// a lot but finitely.
inline double interleaved_pair_cost(int i, int j, const glm::dvec3& a, const glm::dvec3& b, double motion_weight) {
    return interleaved_neighbour_weight(i, j) / std::max(interleaved_tuple_distance(a, b, motion_weight), 1e-3);
}

namespace detail {

// Host-side deterministic random numbers (std:: distributions differ between
// standard libraries).
class TileRandom {
public:
    explicit TileRandom(std::uint32_t seed) : state_(patternsd::bc_hash(seed ^ 0x6d2b79f5u)) {}
    std::uint32_t next() { return patternsd::bc_hash3(state_, counter_++, 0x1f123bb5u); }
    // Uniform enough in [0, n) for the small n used here.
    int below(int n) { return static_cast<int>(next() % static_cast<std::uint32_t>(n)); }
    template <class T>
    void shuffle(std::vector<T>& items) {
        for (std::size_t i = items.size(); i > 1; --i) {
            const auto j = static_cast<std::size_t>(below(static_cast<int>(i)));
            std::swap(items[i - 1], items[j]);
        }
    }

private:
    std::uint32_t state_;
    std::uint32_t counter_ = 0;
};

// A square of lattice cells around one tile, coordinates -1 .. width (the tile
// is 0 .. width-1, -1 and width are the neighbouring tiles' cells). -1 = empty.
class TileCanvas {
public:
    explicit TileCanvas(int width) : width_(width), side_(width + 2), cells_(std::size_t(side_) * std::size_t(side_), -1) {}
    bool inside(int x, int y) const { return x >= -1 && x <= width_ && y >= -1 && y <= width_; }
    int get(int x, int y) const { return inside(x, y) ? cells_[index(x, y)] : -1; }
    void set(int x, int y, int tuple) { cells_[index(x, y)] = tuple; }

    // Sum of w / d between `tuple` placed at (x, y) and the filled cells of the window.
    double cost(int x, int y, int tuple, const InterleavedTiles& tiles) const {
        double sum = 0.0;
        for (int j = -tiles.radius; j <= tiles.radius; ++j) {
            for (int i = -tiles.radius; i <= tiles.radius; ++i) {
                if (i == 0 && j == 0) continue;
                const int other = get(x + i, y + j);
                if (other < 0) continue;
                sum += interleaved_pair_cost(i, j, tiles.tuples[std::size_t(tuple)], tiles.tuples[std::size_t(other)],
                                             tiles.motion_weight);
            }
        }
        return sum;
    }

private:
    std::size_t index(int x, int y) const { return std::size_t(y + 1) * std::size_t(side_) + std::size_t(x + 1); }
    int width_;
    int side_;
    std::vector<int> cells_;
};

// The cheapest candidate for cell (x, y); ties go to the earliest candidate.
inline int cheapest_tuple(const TileCanvas& canvas, int x, int y, const std::vector<int>& candidates,
                          const InterleavedTiles& tiles) {
    int best = candidates.front();
    double best_cost = canvas.cost(x, y, best, tiles);
    for (std::size_t c = 1; c < candidates.size(); ++c) {
        const double cost = canvas.cost(x, y, candidates[c], tiles);
        if (cost < best_cost) {
            best_cost = cost;
            best = candidates[c];
        }
    }
    return best;
}

// Roles of a tile's boundary cells: its four corner cells and four edge rows.
enum TileRole { role_tl, role_tr, role_bl, role_br, role_top, role_bottom, role_left, role_right, role_count };

struct TileBoundary {
    // corner[colour][role_tl .. role_br]: the 2 x 2 block around a lattice
    // corner of that colour; entry role_tl is the top-left cell of the tile
    // below-right of the corner, role_br the bottom-right cell of the tile
    // above-left of it, and so on.
    std::vector<std::vector<int>> corner;
    // horizontal[c_left * 3 + c_right]: the strip along a horizontal tile edge
    // between corners of those colours; above[x - 1] is cell (x, width - 1) of
    // the tile above, below[x - 1] cell (x, 0) of the tile below, x = 1 .. width-2.
    std::vector<std::vector<int>> h_above, h_below;
    // vertical[c_top * 3 + c_bottom]: left[y - 1] is cell (width - 1, y) of the
    // tile on the left, right[y - 1] cell (0, y) of the tile on the right.
    std::vector<std::vector<int>> v_left, v_right;
};

// Where the cells of the 2 x 2 block around a lattice corner lie, relative to
// the corner, by role (role_tl .. role_br): the tile below-right of the corner
// starts at the corner itself.
constexpr int corner_block_dx[4] = {0, -1, 0, -1};
constexpr int corner_block_dy[4] = {0, 0, -1, -1};

// Puts a corner block (TileBoundary::corner[colour]) around canvas point (x, y).
inline void paint_corner_block(TileCanvas& canvas, const std::vector<int>& block, int x, int y) {
    for (int role = role_tl; role <= role_br; ++role) {
        canvas.set(x + corner_block_dx[role], y + corner_block_dy[role], block[std::size_t(role)]);
    }
}

// Puts the boundary cells that corner colours fix around a tile with corner
// colours (tl, tr, bl, br) onto the canvas (tile cells and the ring outside).
inline void paint_boundary(TileCanvas& canvas, const TileBoundary& boundary, int width, const int colours[4]) {
    const int corner_x[4] = {0, width, 0, width};
    const int corner_y[4] = {0, 0, width, width};
    for (int c = 0; c < 4; ++c) {
        paint_corner_block(canvas, boundary.corner[std::size_t(colours[c])], corner_x[c], corner_y[c]);
    }
    const std::size_t top = std::size_t(colours[0] * 3 + colours[1]);
    const std::size_t bottom = std::size_t(colours[2] * 3 + colours[3]);
    const std::size_t left = std::size_t(colours[0] * 3 + colours[2]);
    const std::size_t right = std::size_t(colours[1] * 3 + colours[3]);
    for (int k = 1; k + 1 < width; ++k) {
        const std::size_t e = std::size_t(k - 1);
        canvas.set(k, -1, boundary.h_above[top][e]);
        canvas.set(k, 0, boundary.h_below[top][e]);
        canvas.set(k, width - 1, boundary.h_above[bottom][e]);
        canvas.set(k, width, boundary.h_below[bottom][e]);
        canvas.set(-1, k, boundary.v_left[left][e]);
        canvas.set(0, k, boundary.v_right[left][e]);
        canvas.set(width - 1, k, boundary.v_left[right][e]);
        canvas.set(width, k, boundary.v_right[right][e]);
    }
}

// Puts the cheapest tuple of `pool` into `cell` and takes it out of the pool.
inline void place_cheapest(TileCanvas& canvas, std::pair<int, int> cell, std::vector<int>& pool,
                           const InterleavedTiles& tiles) {
    const int tuple = cheapest_tuple(canvas, cell.first, cell.second, pool, tiles);
    canvas.set(cell.first, cell.second, tuple);
    pool.erase(std::find(pool.begin(), pool.end(), tuple));
}

// Greedy fill of `cells` (in random order) from `pool`, each tuple at most once.
inline void fill_greedy(TileCanvas& canvas, std::vector<std::pair<int, int>> cells, std::vector<int> pool,
                        const InterleavedTiles& tiles, TileRandom& random) {
    random.shuffle(cells);
    for (const auto& cell : cells) place_cheapest(canvas, cell, pool, tiles);
}

// The role pools: one colour per corner-cell tuple when they fit (3 per
// corner role), edge rows share what is left out equally; the rest only goes
// inside. pool[role] for role_tl .. role_right.
inline std::vector<std::vector<int>> make_role_pools(int n, int edge, TileRandom& random) {
    std::vector<int> order(static_cast<std::size_t>(n));
    for (int k = 0; k < n; ++k) order[std::size_t(k)] = k;
    random.shuffle(order);
    const int corner_pool = std::min(3, (n - 4 * edge) / 4);
    const int edge_pool = edge == 0 ? 0 : (n - 4 * corner_pool) / 4;
    std::vector<std::vector<int>> pool(role_count);
    std::size_t next = 0;
    for (int role = 0; role < role_count; ++role) {
        const int size = role < 4 ? corner_pool : edge_pool;
        for (int i = 0; i < size; ++i) pool[std::size_t(role)].push_back(order[next++]);
    }
    return pool;
}

// Corner blocks, one per colour, tuples differing between colours while the pool lasts.
inline void make_corner_blocks(TileBoundary& boundary, const std::vector<std::vector<int>>& pool,
                               const InterleavedTiles& tiles, TileRandom& random) {
    boundary.corner.assign(BC_INTERLEAVED_COLOURS, std::vector<int>(4, -1));
    std::vector<std::vector<int>> used_by_colours(4);
    for (std::size_t colour = 0; colour < BC_INTERLEAVED_COLOURS; ++colour) {
        TileCanvas canvas(tiles.width);
        std::vector<int> roles = {role_tl, role_tr, role_bl, role_br};
        random.shuffle(roles);
        for (int role : roles) {
            std::vector<int> candidates;
            for (int tuple : pool[std::size_t(role)]) {
                const auto& used = used_by_colours[std::size_t(role)];
                if (std::find(used.begin(), used.end(), tuple) == used.end()) candidates.push_back(tuple);
            }
            if (candidates.empty()) candidates = pool[std::size_t(role)];
            // The block straddles corner (1, 1) of the canvas, so every cell is on it.
            const int x = 1 + corner_block_dx[role], y = 1 + corner_block_dy[role];
            const int tuple = cheapest_tuple(canvas, x, y, candidates, tiles);
            canvas.set(x, y, tuple);
            boundary.corner[colour][std::size_t(role)] = tuple;
            used_by_colours[std::size_t(role)].push_back(tuple);
        }
    }
}

// The two rows of cells along one tile edge, x = 1 .. width-2 along it:
// `outer` in the neighbouring tile (across = -1: the tile above, or on the
// left), `inner` in this one (across = 0).
struct EdgeStrip {
    std::vector<int> outer, inner;
};

enum class EdgeAxis { horizontal, vertical };

// The strip along a tile edge between corners of colours `first` (at canvas
// point (0, 0)) and `second` (the edge's other end), next to their two corner
// blocks: both rows in one random order, each row from its own pool. The
// horizontal edge lists its cells row by row, the vertical one cell pair by
// cell pair; the order feeds the shuffle, so both stay as they always were
// (the tile set is part of every interleave render).
inline EdgeStrip make_edge_strip(const TileBoundary& boundary, int first, int second, EdgeAxis axis,
                                 const std::vector<int>& outer_pool, const std::vector<int>& inner_pool,
                                 const InterleavedTiles& tiles, TileRandom& random) {
    const int width = tiles.width;
    const int edge = width - 2;
    const bool horizontal = axis == EdgeAxis::horizontal;
    // Canvas cell `along` the edge and `across` it.
    auto at = [horizontal](int along, int across) {
        return horizontal ? std::make_pair(along, across) : std::make_pair(across, along);
    };
    TileCanvas canvas(width);
    const std::pair<int, int> far_corner = at(width, 0);
    paint_corner_block(canvas, boundary.corner[std::size_t(first)], 0, 0);
    paint_corner_block(canvas, boundary.corner[std::size_t(second)], far_corner.first, far_corner.second);
    std::vector<std::pair<int, int>> cells;
    for (int k = 1; k <= edge; ++k) {
        cells.push_back(at(k, -1));
        if (!horizontal) cells.push_back(at(k, 0));
    }
    for (int k = 1; k <= edge && horizontal; ++k) cells.push_back(at(k, 0));
    random.shuffle(cells);
    std::vector<int> outer_left = outer_pool, inner_left = inner_pool;
    for (const auto& cell : cells) {
        const bool outer = (horizontal ? cell.second : cell.first) < 0;
        place_cheapest(canvas, cell, outer ? outer_left : inner_left, tiles);
    }
    EdgeStrip strip;
    for (int k = 1; k <= edge; ++k) {
        const std::pair<int, int> outer = at(k, -1), inner = at(k, 0);
        strip.outer.push_back(canvas.get(outer.first, outer.second));
        strip.inner.push_back(canvas.get(inner.first, inner.second));
    }
    return strip;
}

// Edge strips, per pair of corner colours: horizontal[first * 3 + second] has
// the row of the tile above from the bottom-row pool and the tile's own top
// row from the top-row pool; vertical likewise with left and right.
inline void make_edge_strips(TileBoundary& boundary, const std::vector<std::vector<int>>& pool,
                             const InterleavedTiles& tiles, TileRandom& random) {
    const int edge = tiles.width - 2;
    const std::size_t pairs = BC_INTERLEAVED_COLOURS * BC_INTERLEAVED_COLOURS;
    boundary.h_above.assign(pairs, {});
    boundary.h_below.assign(pairs, {});
    boundary.v_left.assign(pairs, {});
    boundary.v_right.assign(pairs, {});
    for (int first = 0; first < 3 && edge > 0; ++first) {
        for (int second = 0; second < 3; ++second) {
            const std::size_t pair = std::size_t(first * 3 + second);
            EdgeStrip h = make_edge_strip(boundary, first, second, EdgeAxis::horizontal, pool[role_bottom],
                                          pool[role_top], tiles, random);
            boundary.h_above[pair] = std::move(h.outer);
            boundary.h_below[pair] = std::move(h.inner);
            EdgeStrip v = make_edge_strip(boundary, first, second, EdgeAxis::vertical, pool[role_right],
                                          pool[role_left], tiles, random);
            boundary.v_left[pair] = std::move(v.outer);
            boundary.v_right[pair] = std::move(v.inner);
        }
    }
}

// Prototype `prototype` (corner colours from its digits in base 3): its
// boundary painted, its interior filled from the tuples the boundary left,
// written into tiles.slot_tuple and tiles.tuple_slot.
inline void make_prototype(InterleavedTiles& tiles, const TileBoundary& boundary, int prototype, TileRandom& random) {
    const int width = tiles.width;
    const int n = tiles.tuple_count;
    const int colours[4] = {prototype % 3, prototype / 3 % 3, prototype / 9 % 3, prototype / 27 % 3};
    TileCanvas canvas(width);
    paint_boundary(canvas, boundary, width, colours);
    std::vector<bool> taken(std::size_t(n), false);
    std::vector<std::pair<int, int>> interior;
    for (int y = 0; y < width; ++y) {
        for (int x = 0; x < width; ++x) {
            const bool on_boundary = x == 0 || y == 0 || x == width - 1 || y == width - 1;
            if (!on_boundary) {
                interior.emplace_back(x, y);
                continue;
            }
            const int tuple = canvas.get(x, y);
            if (tuple < 0 || taken[std::size_t(tuple)]) {
                throw std::logic_error("interleaved tiles: boundary pools overlap (a bug)");
            }
            taken[std::size_t(tuple)] = true;
        }
    }
    std::vector<int> rest;
    for (int k = 0; k < n; ++k) {
        if (!taken[std::size_t(k)]) rest.push_back(k);
    }
    if (!interior.empty()) fill_greedy(canvas, interior, rest, tiles, random);
    const std::size_t base = std::size_t(prototype) * std::size_t(n);
    for (int y = 0; y < width; ++y) {
        for (int x = 0; x < width; ++x) {
            const int tuple = canvas.get(x, y);
            const std::size_t slot = std::size_t(y * width + x);
            tiles.slot_tuple[base + slot] = static_cast<std::uint16_t>(tuple);
            tiles.tuple_slot[base + std::size_t(tuple)] = static_cast<std::uint16_t>(slot);
        }
    }
}

}  // namespace detail

// Builds the 81 prototype tiles. Matching rule (docs/sampling.md): the 2 x 2
// cells around a lattice corner depend only on the corner's colour, the two
// rows (columns) of cells along a tile edge only on the colours of the edge's
// two corners; the interior is free. Every boundary role (corner cell, edge
// row) draws from its own pool of tuples, so a tile never holds a tuple
// twice; the interior takes the tuples its boundary left. Each stage fills its
// cells greedily in random order, each cell taking the unused tuple of its
// pool that minimises the sum of w / d over the (2 radius + 1)^2 window of
// cells already fixed — including the neighbouring tiles' cells that the
// corner colours fix. Throws std::invalid_argument for width outside [2, 16],
// radius outside [1, 8] or motion_weight outside [0, 1].
inline InterleavedTiles make_interleaved_tiles(const InterleavedTileOptions& options) {
    using namespace detail;
    if (options.width < 2 || options.width > 16) {
        throw std::invalid_argument("interleaved tile width must be in [2, 16], got " + std::to_string(options.width));
    }
    if (options.radius < 1 || options.radius > 8) {
        throw std::invalid_argument("interleaved neighbourhood radius must be in [1, 8], got " +
                                    std::to_string(options.radius));
    }
    if (!(options.motion_weight >= 0.0 && options.motion_weight <= 1.0)) {
        throw std::invalid_argument("interleaved motion weight q must be in [0, 1], got " +
                                    std::to_string(options.motion_weight));
    }
    const int width = options.width;
    const int n = width * width;
    InterleavedTiles tiles;
    tiles.width = width;
    tiles.tuple_count = n;
    tiles.radius = options.radius;
    tiles.motion_weight = options.motion_weight;
    tiles.seed = options.seed;
    for (int k = 0; k < n; ++k) tiles.tuples.push_back(glm::dvec3(patternsd::interleaved_tuple(std::uint32_t(k))));
    // One generator through every stage, in this order: the tile set is a
    // function of the seed alone.
    TileRandom random(options.seed);
    const std::vector<std::vector<int>> pool = make_role_pools(n, width - 2, random);
    TileBoundary boundary;
    make_corner_blocks(boundary, pool, tiles, random);
    make_edge_strips(boundary, pool, tiles, random);
    tiles.slot_tuple.assign(std::size_t(InterleavedTiles::prototype_count) * std::size_t(n), 0);
    tiles.tuple_slot.assign(tiles.slot_tuple.size(), 0);
    for (int prototype = 0; prototype < InterleavedTiles::prototype_count; ++prototype) {
        make_prototype(tiles, boundary, prototype, random);
    }
    return tiles;
}

// The tuples of a region of tiles_x x tiles_y tiles from tile (0, 0): element
// gy * (tiles_x width) + gx is the tuple of lattice cell (gx, gy).
inline std::vector<int> assemble_interleaved_lattice(const InterleavedTiles& tiles, int tiles_x, int tiles_y) {
    if (tiles_x < 1 || tiles_y < 1) throw std::invalid_argument("interleaved lattice needs at least 1x1 tiles");
    const int lattice_w = tiles_x * tiles.width, lattice_h = tiles_y * tiles.width;
    std::vector<int> lattice(std::size_t(lattice_w) * std::size_t(lattice_h));
    for (int gy = 0; gy < lattice_h; ++gy) {
        for (int gx = 0; gx < lattice_w; ++gx) {
            lattice[std::size_t(gy) * std::size_t(lattice_w) + std::size_t(gx)] =
                tiles.tuple_at(std::uint32_t(gx), std::uint32_t(gy));
        }
    }
    return lattice;
}

// The optimisation's cost of a lattice of tuples (lattice_w x lattice_h cells,
// row-major): the mean over cells of the sum of w / d over the other cells of
// its (2 radius + 1)^2 window that lie in the lattice.
inline double interleaved_lattice_cost(const std::vector<int>& lattice, int lattice_w, int lattice_h,
                                       const std::vector<glm::dvec3>& tuples, double motion_weight, int radius) {
    if (lattice_w < 1 || lattice_h < 1 || lattice.size() != std::size_t(lattice_w) * std::size_t(lattice_h)) {
        throw std::invalid_argument("interleaved lattice cost: lattice size does not match its dimensions");
    }
    double total = 0.0;
    for (int y = 0; y < lattice_h; ++y) {
        for (int x = 0; x < lattice_w; ++x) {
            const glm::dvec3& here = tuples.at(std::size_t(lattice[std::size_t(y) * std::size_t(lattice_w) + std::size_t(x)]));
            for (int j = -radius; j <= radius; ++j) {
                for (int i = -radius; i <= radius; ++i) {
                    if ((i == 0 && j == 0) || x + i < 0 || y + j < 0 || x + i >= lattice_w || y + j >= lattice_h) continue;
                    const int other = lattice[std::size_t(y + j) * std::size_t(lattice_w) + std::size_t(x + i)];
                    total += interleaved_pair_cost(i, j, here, tuples.at(std::size_t(other)), motion_weight);
                }
            }
        }
    }
    return total / double(lattice.size());
}

}  // namespace blurcull
