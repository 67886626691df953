// blurcull::patterns<Real>: sample patterns (random, jittered, Owen-scrambled
// Sobol) and the per-sample part of interleaved sampling, in the shared
// C++/GLSL dialect (detail/patterns_body.inl); and, host-only, the
// construction of the colour-cornered interleaved tile set (Aqsis 2.0 core,
// Fatahalian et al. 2009, Lagae and Dutré's corner tiles). docs/sampling.md
// explains the patterns, the tile construction and its matching rule.
#pragma once

#include "kernel.hpp"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace blurcull {

// The shared text needs the names kernel<Real> defines (the GLSL built-ins,
// bc_hash, PixelSample, pixel_sample, ...); a derived class template sees
// them only through these using-declarations.
template <class Real>
struct patterns : kernel<Real> {
    using base = kernel<Real>;
    using real = typename base::real;
    using vec2 = typename base::vec2;
    using vec3 = typename base::vec3;
    using vec4 = typename base::vec4;
    using uint = typename base::uint;
    using PixelSample = typename base::PixelSample;
    using base::abs;
    using base::bc_epsilon;
    using base::bc_hash;
    using base::bc_hash3;
    using base::bc_square_to_disk;
    using base::bc_unit;
    using base::clamp;
    using base::cos;
    using base::max;
    using base::min;
    using base::pixel_sample;
    using base::sin;
    using base::sqrt;

#include "detail/patterns_body.inl"
};

using patternsf = patterns<float>;
using patternsd = patterns<double>;

// ---- host side: pattern names and textures ----------------------------------

inline const char* sample_pattern_name(int pattern) {
    switch (pattern) {
        case BC_PATTERN_HASHED: return "hashed";
        case BC_PATTERN_RANDOM: return "random";
        case BC_PATTERN_JITTERED: return "jittered";
        case BC_PATTERN_SOBOL: return "sobol";
        default: return "unknown";
    }
}

// "hashed", "random", "jittered" or "sobol" -> BC_PATTERN_*. Throws
// std::invalid_argument naming the valid patterns otherwise.
inline int parse_sample_pattern(const std::string& name) {
    for (int pattern : {BC_PATTERN_HASHED, BC_PATTERN_RANDOM, BC_PATTERN_JITTERED, BC_PATTERN_SOBOL}) {
        if (name == sample_pattern_name(pattern)) return pattern;
    }
    throw std::invalid_argument("unknown sample pattern '" + name + "' (valid: hashed, random, jittered, sobol)");
}

// The texture a GPU can read instead of evaluating the pattern: sample j of
// pixel (px, py) of the pattern tiled every `tile` pixels is element
// ((py % tile) * tile + px % tile) * spp + j (= patternsf::pattern_sample_tiled).
// Throws std::invalid_argument for an unknown pattern, tile < 1 or spp < 1.
inline std::vector<kernelf::PixelSample> make_pattern_tile(int pattern, int tile, int spp, std::uint32_t seed) {
    if (std::string(sample_pattern_name(pattern)) == "unknown") {
        throw std::invalid_argument("unknown sample pattern id " + std::to_string(pattern));
    }
    if (tile < 1 || tile > 4096) throw std::invalid_argument("pattern tile size must be in [1, 4096], got " + std::to_string(tile));
    if (spp < 1 || spp > 65536) throw std::invalid_argument("samples per pixel must be in [1, 65536], got " + std::to_string(spp));
    std::vector<kernelf::PixelSample> texels;
    texels.reserve(static_cast<std::size_t>(tile) * static_cast<std::size_t>(tile) * static_cast<std::size_t>(spp));
    const auto side = static_cast<std::uint32_t>(tile);
    const auto count = static_cast<std::uint32_t>(spp);
    for (std::uint32_t py = 0; py < side; ++py) {
        for (std::uint32_t px = 0; px < side; ++px) {
            for (std::uint32_t j = 0; j < count; ++j) texels.push_back(patternsf::pattern_sample(pattern, px, py, j, count, seed));
        }
    }
    return texels;
}

// ---- host side: interleaved tile sets ------------------------------------------

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

// Puts the boundary cells that corner colours fix around a tile with corner
// colours (tl, tr, bl, br) onto the canvas (tile cells and the ring outside).
inline void paint_boundary(TileCanvas& canvas, const TileBoundary& boundary, int width, const int colours[4]) {
    const int corner_x[4] = {0, width, 0, width};
    const int corner_y[4] = {0, 0, width, width};
    for (int c = 0; c < 4; ++c) {
        const std::vector<int>& block = boundary.corner[std::size_t(colours[c])];
        const int x = corner_x[c], y = corner_y[c];
        canvas.set(x, y, block[role_tl]);
        canvas.set(x - 1, y, block[role_tr]);
        canvas.set(x, y - 1, block[role_bl]);
        canvas.set(x - 1, y - 1, block[role_br]);
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

// Greedy fill of `cells` (in random order) from `pool`, each tuple at most once.
inline void fill_greedy(TileCanvas& canvas, std::vector<std::pair<int, int>> cells, std::vector<int> pool,
                        const InterleavedTiles& tiles, TileRandom& random) {
    random.shuffle(cells);
    for (const auto& cell : cells) {
        const int tuple = cheapest_tuple(canvas, cell.first, cell.second, pool, tiles);
        canvas.set(cell.first, cell.second, tuple);
        pool.erase(std::find(pool.begin(), pool.end(), tuple));
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
    const int edge = width - 2;  // cells per edge row, corners excluded
    InterleavedTiles tiles;
    tiles.width = width;
    tiles.tuple_count = n;
    tiles.radius = options.radius;
    tiles.motion_weight = options.motion_weight;
    tiles.seed = options.seed;
    for (int k = 0; k < n; ++k) tiles.tuples.push_back(glm::dvec3(patternsd::interleaved_tuple(std::uint32_t(k))));
    TileRandom random(options.seed);

    // Pools: one colour per corner-cell tuple when they fit (3 per corner role),
    // edge rows share what is left out equally; the rest only goes inside.
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

    // Corner blocks, one per colour, tuples differing between colours while the pool lasts.
    TileBoundary boundary;
    boundary.corner.assign(BC_INTERLEAVED_COLOURS, std::vector<int>(4, -1));
    std::vector<std::vector<int>> used_by_colours(4);
    for (std::size_t colour = 0; colour < BC_INTERLEAVED_COLOURS; ++colour) {
        TileCanvas canvas(width);
        std::vector<int> roles = {role_tl, role_tr, role_bl, role_br};
        random.shuffle(roles);
        const int dx[4] = {0, -1, 0, -1};
        const int dy[4] = {0, 0, -1, -1};
        for (int role : roles) {
            std::vector<int> candidates;
            for (int tuple : pool[std::size_t(role)]) {
                const auto& used = used_by_colours[std::size_t(role)];
                if (std::find(used.begin(), used.end(), tuple) == used.end()) candidates.push_back(tuple);
            }
            if (candidates.empty()) candidates = pool[std::size_t(role)];
            // The block straddles corner (1, 1) of the canvas, so every cell is on it.
            const int x = 1 + dx[role], y = 1 + dy[role];
            const int tuple = cheapest_tuple(canvas, x, y, candidates, tiles);
            canvas.set(x, y, tuple);
            boundary.corner[colour][std::size_t(role)] = tuple;
            used_by_colours[std::size_t(role)].push_back(tuple);
        }
    }

    // Edge strips, per pair of corner colours, next to their two corner blocks.
    const std::size_t pairs = BC_INTERLEAVED_COLOURS * BC_INTERLEAVED_COLOURS;
    boundary.h_above.assign(pairs, {});
    boundary.h_below.assign(pairs, {});
    boundary.v_left.assign(pairs, {});
    boundary.v_right.assign(pairs, {});
    for (int first = 0; first < 3 && edge > 0; ++first) {
        for (int second = 0; second < 3; ++second) {
            const std::size_t pair = std::size_t(first * 3 + second);
            // Horizontal: the canvas's row -1 / 0 are the tile above / below;
            // corners (0, 0) and (width, 0) have colours first and second.
            {
                TileCanvas canvas(width);
                for (int c = 0; c < 2; ++c) {
                    const std::vector<int>& block = boundary.corner[std::size_t(c == 0 ? first : second)];
                    const int x = c == 0 ? 0 : width;
                    canvas.set(x, 0, block[role_tl]);
                    canvas.set(x - 1, 0, block[role_tr]);
                    canvas.set(x, -1, block[role_bl]);
                    canvas.set(x - 1, -1, block[role_br]);
                }
                std::vector<std::pair<int, int>> above, below;
                for (int k = 1; k <= edge; ++k) {
                    above.emplace_back(k, -1);
                    below.emplace_back(k, 0);
                }
                // Both rows in one random order, each from its own pool.
                std::vector<std::pair<int, int>> cells = above;
                cells.insert(cells.end(), below.begin(), below.end());
                random.shuffle(cells);
                std::vector<int> pool_above = pool[role_bottom], pool_below = pool[role_top];
                for (const auto& cell : cells) {
                    std::vector<int>& from = cell.second < 0 ? pool_above : pool_below;
                    const int tuple = cheapest_tuple(canvas, cell.first, cell.second, from, tiles);
                    canvas.set(cell.first, cell.second, tuple);
                    from.erase(std::find(from.begin(), from.end(), tuple));
                }
                for (int k = 1; k <= edge; ++k) {
                    boundary.h_above[pair].push_back(canvas.get(k, -1));
                    boundary.h_below[pair].push_back(canvas.get(k, 0));
                }
            }
            // Vertical: column -1 / 0 are the tile left / right; corners (0, 0)
            // and (0, width) have colours first (top) and second (bottom).
            {
                TileCanvas canvas(width);
                for (int c = 0; c < 2; ++c) {
                    const std::vector<int>& block = boundary.corner[std::size_t(c == 0 ? first : second)];
                    const int y = c == 0 ? 0 : width;
                    canvas.set(0, y, block[role_tl]);
                    canvas.set(-1, y, block[role_tr]);
                    canvas.set(0, y - 1, block[role_bl]);
                    canvas.set(-1, y - 1, block[role_br]);
                }
                std::vector<std::pair<int, int>> cells;
                for (int k = 1; k <= edge; ++k) {
                    cells.emplace_back(-1, k);
                    cells.emplace_back(0, k);
                }
                random.shuffle(cells);
                std::vector<int> pool_left = pool[role_right], pool_right = pool[role_left];
                for (const auto& cell : cells) {
                    std::vector<int>& from = cell.first < 0 ? pool_left : pool_right;
                    const int tuple = cheapest_tuple(canvas, cell.first, cell.second, from, tiles);
                    canvas.set(cell.first, cell.second, tuple);
                    from.erase(std::find(from.begin(), from.end(), tuple));
                }
                for (int k = 1; k <= edge; ++k) {
                    boundary.v_left[pair].push_back(canvas.get(-1, k));
                    boundary.v_right[pair].push_back(canvas.get(0, k));
                }
            }
        }
    }

    // Prototypes: boundary painted, interior filled from what it left.
    tiles.slot_tuple.assign(std::size_t(InterleavedTiles::prototype_count) * std::size_t(n), 0);
    tiles.tuple_slot.assign(tiles.slot_tuple.size(), 0);
    for (int prototype = 0; prototype < InterleavedTiles::prototype_count; ++prototype) {
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
