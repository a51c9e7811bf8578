#include "energy/assembly_pattern.hpp"

#include <algorithm>
#include <numeric>
#include <string>

#include "core/collective_error.hpp"

namespace neomesh {

namespace {

// The cells around each local vertex, as CSR over vertices (cells numbered as in MeshView).
struct VertexCells {
  std::vector<PetscInt> start, cells;
  std::vector<const PetscInt*> cell_vertices;  // per cell
  std::vector<int> cell_size;                  // vertices per cell

  explicit VertexCells(const MeshView& view)
      : start(view.num_vertices + 1, 0), cell_vertices(view.num_cells), cell_size(view.num_cells) {
    for (const CellBlock& block : view.blocks)
      for (PetscInt c = 0; c < block.size(); ++c) {
        cell_vertices[block.first_cell + c] = block.cell(c);
        cell_size[block.first_cell + c] = block.nodes();
        for (int i = 0; i < block.nodes(); ++i) ++start[block.cell(c)[i] + 1];
      }
    std::partial_sum(start.begin(), start.end(), start.begin());
    cells.resize(start.back());
    std::vector<PetscInt> next(start.begin(), start.end() - 1);
    for (PetscInt cell = 0; cell < view.num_cells; ++cell)
      for (int i = 0; i < cell_size[cell]; ++i) cells[next[cell_vertices[cell][i]]++] = cell;
  }
};

// Greedy colouring of the chunks of one block (AssemblyPattern::kChunk consecutive cells):
// each chunk takes the smallest colour that no earlier chunk sharing a vertex with it has.
std::vector<PetscInt> colour_block_chunks(const VertexCells& around, const CellBlock& block) {
  const PetscInt chunks = (block.size() + AssemblyPattern::kChunk - 1) / AssemblyPattern::kChunk;
  const PetscInt first = block.first_cell, end = block.first_cell + block.size();
  // First, on every thread, the earlier chunks that share a vertex with each chunk (visiting
  // the cells around a chunk's vertices is most of the work); then the greedy pass in order.
  std::vector<std::vector<PetscInt>> earlier(chunks);
#pragma omp parallel
  {
    std::vector<PetscInt> seen_by(chunks, -1);  // seen_by[k] == chunk: k is in earlier[chunk]
#pragma omp for schedule(static)
    for (PetscInt chunk = 0; chunk < chunks; ++chunk) {
      const PetscInt cells_end = std::min(end, first + (chunk + 1) * AssemblyPattern::kChunk);
      for (PetscInt cell = first + chunk * AssemblyPattern::kChunk; cell < cells_end; ++cell)
        for (int i = 0; i < around.cell_size[cell]; ++i) {
          const PetscInt v = around.cell_vertices[cell][i];
          for (PetscInt k = around.start[v]; k < around.start[v + 1]; ++k) {
            const PetscInt other = around.cells[k];
            if (other < first || other >= end) continue;  // another block
            const PetscInt near = (other - first) / AssemblyPattern::kChunk;
            if (near >= chunk || seen_by[near] == chunk) continue;
            seen_by[near] = chunk;
            earlier[chunk].push_back(near);
          }
        }
    }
  }
  std::vector<PetscInt> colour(chunks, -1);
  std::vector<PetscInt> taken_by;  // taken_by[k] == chunk: colour k is taken near `chunk`
  for (PetscInt chunk = 0; chunk < chunks; ++chunk) {
    for (const PetscInt near : earlier[chunk]) {
      const PetscInt taken = colour[near];
      if (taken >= static_cast<PetscInt>(taken_by.size())) taken_by.resize(taken + 1, -1);
      taken_by[taken] = chunk;
    }
    PetscInt k = 0;
    while (k < static_cast<PetscInt>(taken_by.size()) && taken_by[k] == chunk) ++k;
    colour[chunk] = k;
  }
  return colour;
}

// Sorted vertex lists as CSR: list i is value[start[i] .. start[i+1]).
struct Lists {
  std::vector<PetscInt> start{0}, value;

  PetscInt size(PetscInt i) const { return start[i + 1] - start[i]; }
  const PetscInt* begin(PetscInt i) const { return value.data() + start[i]; }
};

// The lists collect(i, buffer, scratch) leaves (sorted, unique) for i < n; each thread has its
// own Scratch. Two passes, counting then filling, keep it parallel without allocations.
template <typename Scratch, typename Collect>
Lists make_lists(PetscInt n, Collect&& collect) {
  Lists lists;
  lists.start.assign(n + 1, 0);
#pragma omp parallel
  {
    std::vector<PetscInt> buffer;
    Scratch scratch;
#pragma omp for schedule(static)
    for (PetscInt i = 0; i < n; ++i) {
      collect(i, buffer, scratch);
      lists.start[i + 1] = static_cast<PetscInt>(buffer.size());
    }
#pragma omp single
    {
      std::partial_sum(lists.start.begin(), lists.start.end(), lists.start.begin());
      lists.value.resize(lists.start.back());
    }
#pragma omp for schedule(static)
    for (PetscInt i = 0; i < n; ++i) {
      collect(i, buffer, scratch);
      std::copy(buffer.begin(), buffer.end(), lists.value.begin() + lists.start[i]);
    }
  }
  return lists;
}

// Per local vertex, the stamp of the last collect call that listed it: the vertices of
// the cells around a vertex (some 100 in a tet mesh) are made unique before the ~15 left are
// sorted, not after.
struct Marks {
  std::vector<PetscInt> stamp;
  PetscInt current = 0;
};

struct NoScratch {};

void sort_unique(std::vector<PetscInt>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

// Where the blocks of one row go: the neighbours [diagonal_begin, diagonal_end) of its sorted
// list, the vertices of the rank that holds the row, to A (or G) from `first`; the others to B
// from `off_first`. Blocks of a row are dim entries apart.
struct RowPlace {
  const PetscInt* list;
  PetscInt size, diagonal_begin, diagonal_end, first, off_first;

  // The entry of (dof 0 of the row's vertex, dof 0 of w) in A or G, or e < 0 for ~e in B.
  PetscInt entry(PetscInt w, int dim) const {
    const PetscInt k = std::lower_bound(list, list + size, w) - list;
    if (k >= diagonal_begin && k < diagonal_end) return first + dim * (k - diagonal_begin);
    return ~(off_first + dim * (k < diagonal_begin ? k : k - (diagonal_end - diagonal_begin)));
  }
};

// Global vertex numbers (global dof / dim) and the order of this rank's rows: "items" are the
// owned vertices in global order (item = row), then the ghosts in local order.
struct Numbering {
  PetscInt first = 0, owned = 0;     // this rank owns global vertices [first, first + owned)
  std::vector<PetscInt> rank_first;  // per rank, then the total: its first global vertex
  std::vector<PetscInt> global;      // per local vertex
  std::vector<PetscInt> item;        // per local vertex
  std::vector<PetscInt> local;       // per item: local vertex

  PetscInt num_ghosts() const { return static_cast<PetscInt>(local.size()) - owned; }
  bool is_owned(PetscInt g) const { return g >= first && g < first + owned; }
  int owner(PetscInt g) const {
    return static_cast<int>(std::upper_bound(rank_first.begin(), rank_first.end(), g) -
                            rank_first.begin() - 1);
  }
};

Numbering number_vertices(const MeshView& view, const DofMap& dofs) {
  const int d = dofs.dim();
  MPI_Comm comm = dofs.comm();
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  Numbering n;
  n.owned = dofs.num_owned_dofs() / d;
  n.rank_first.resize(ranks + 1, 0);
  MPI_Allgather(&n.owned, 1, MPIU_INT, n.rank_first.data() + 1, 1, MPIU_INT, comm);
  std::partial_sum(n.rank_first.begin(), n.rank_first.end(), n.rank_first.begin());
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  n.first = n.rank_first[rank];

  const PetscInt nv = view.num_vertices;
  const std::vector<PetscInt>& global_dof = dofs.global_dof();
  n.global.resize(nv);
  n.item.resize(nv);
  n.local.assign(n.owned, -1);
  std::string error;  // collective: a rank alone failing would leave the others waiting
  for (PetscInt v = 0; v < nv && error.empty(); ++v) {
    const PetscInt g = global_dof[d * v] / d;
    bool consecutive = global_dof[d * v] % d == 0;
    for (int a = 1; a < d; ++a) consecutive = consecutive && global_dof[d * v + a] == d * g + a;
    if (!consecutive || n.is_owned(g) != (view.owned[v] != 0) ||
        (n.is_owned(g) && n.local[g - n.first] >= 0)) {
      error = fmt::format(
          "assembly pattern: the DofMap does not number local vertex {} as one "
          "block of {} dofs of its owner",
          v, d);
      break;
    }
    n.global[v] = g;
    if (!n.is_owned(g)) continue;
    n.item[v] = g - n.first;
    n.local[g - n.first] = v;
  }
  if (error.empty() && std::find(n.local.begin(), n.local.end(), -1) != n.local.end())
    error = "assembly pattern: an owned vertex is missing from the rank's mesh";
  throw_if_any(comm, error);
  for (PetscInt v = 0; v < nv; ++v)
    if (!view.owned[v]) {
      n.item[v] = static_cast<PetscInt>(n.local.size());
      n.local.push_back(v);
    }
  return n;
}

// Sends out[r] to rank r, for every r; returns what the ranks sent here, one after the other
// (from rank r: data[offset[r] .. offset[r + 1])).
struct Received {
  std::vector<PetscInt> data;
  std::vector<int> offset;
};

Received send_to_ranks(MPI_Comm comm, const std::vector<std::vector<PetscInt>>& out) {
  const int ranks = static_cast<int>(out.size());
  std::vector<int> send_count(ranks), send_offset(ranks + 1, 0), count(ranks);
  std::vector<PetscInt> send;
  for (int r = 0; r < ranks; ++r) {
    send_count[r] = static_cast<int>(out[r].size());
    send_offset[r + 1] = send_offset[r] + send_count[r];
    send.insert(send.end(), out[r].begin(), out[r].end());
  }
  MPI_Alltoall(send_count.data(), 1, MPI_INT, count.data(), 1, MPI_INT, comm);
  Received in;
  in.offset.assign(ranks + 1, 0);
  std::partial_sum(count.begin(), count.end(), in.offset.begin() + 1);
  in.data.resize(in.offset.back());
  MPI_Alltoallv(send.data(), send_count.data(), send_offset.data(), MPIU_INT, in.data.data(),
                count.data(), in.offset.data(), MPIU_INT, comm);
  return in;
}

OwnedSF make_sf(MPI_Comm comm, std::size_t roots, const std::vector<PetscInt>& leaves,
                const std::vector<PetscSFNode>& remote) {
  OwnedSF sf;
  NM_PETSC(PetscSFCreate(comm, sf.out()));
  NM_PETSC(PetscSFSetGraph(sf, static_cast<PetscInt>(roots), static_cast<PetscInt>(leaves.size()),
                           const_cast<PetscInt*>(leaves.data()), PETSC_COPY_VALUES,
                           const_cast<PetscSFNode*>(remote.data()), PETSC_COPY_VALUES));
  NM_PETSC(PetscSFSetUp(sf));
  return sf;
}

// The sorted neighbour vertices (global numbers, the vertex itself included) of every owned
// row and every ghost.
struct Neighbours {
  Lists rows, ghosts;
  // After merge_ghost_lists: the lists other ranks sent, (global vertex, size, list...) each.
  Received requests;

  // From this rank's cells.
  Neighbours(const Numbering& num, const VertexCells& around) {
    auto from_cells = [&](PetscInt first_item) {
      return [&, first_item](PetscInt i, std::vector<PetscInt>& out, Marks& marks) {
        const PetscInt v = num.local[first_item + i];
        if (marks.stamp.empty()) marks.stamp.assign(num.local.size(), -1);
        const PetscInt stamp = marks.current++;
        out.clear();
        // A vertex without cells still has its diagonal.
        if (around.start[v] == around.start[v + 1]) out.push_back(num.global[v]);
        for (PetscInt k = around.start[v]; k < around.start[v + 1]; ++k) {
          const PetscInt cell = around.cells[k];
          for (int j = 0; j < around.cell_size[cell]; ++j) {
            const PetscInt w = around.cell_vertices[cell][j];
            if (marks.stamp[w] == stamp) continue;
            marks.stamp[w] = stamp;
            out.push_back(num.global[w]);
          }
        }
        std::sort(out.begin(), out.end());
      };
    };
    rows = make_lists<Marks>(num.owned, from_cells(0));
    ghosts = make_lists<Marks>(num.num_ghosts(), from_cells(num.owned));
  }

  // Collective. Each ghost's list goes to its owner and is merged into the owner's row: the
  // row of a vertex on the interface has the couplings of all its cells.
  void merge_ghost_lists(MPI_Comm comm, const Numbering& num) {
    std::vector<std::vector<PetscInt>> out(num.rank_first.size() - 1);
    for (PetscInt i = 0; i < num.num_ghosts(); ++i) {
      const PetscInt g = num.global[num.local[num.owned + i]];
      std::vector<PetscInt>& to = out[num.owner(g)];
      to.push_back(g);
      to.push_back(ghosts.size(i));
      to.insert(to.end(), ghosts.begin(i), ghosts.begin(i) + ghosts.size(i));
    }
    requests = send_to_ranks(comm, out);
    const std::vector<PetscInt>& in = requests.data;
    std::vector<PetscInt> start(num.owned + 1, 0), list;  // per row: positions in `in`
    for (std::size_t k = 0; k < in.size(); k += 2 + in[k + 1]) ++start[in[k] - num.first + 1];
    std::partial_sum(start.begin(), start.end(), start.begin());
    list.resize(start.back());
    std::vector<PetscInt> next(start.begin(), start.end() - 1);
    for (std::size_t k = 0; k < in.size(); k += 2 + in[k + 1])
      list[next[in[k] - num.first]++] = static_cast<PetscInt>(k);
    auto merge = [&](PetscInt r, std::vector<PetscInt>& merged, NoScratch&) {
      merged.assign(rows.begin(r), rows.begin(r) + rows.size(r));
      if (start[r] == start[r + 1]) return;  // not on the interface
      for (PetscInt k = start[r]; k < start[r + 1]; ++k)
        merged.insert(merged.end(), in.begin() + list[k] + 2,
                      in.begin() + list[k] + 2 + in[list[k] + 1]);
      sort_unique(merged);
    };
    rows = make_lists<NoScratch>(num.owned, merge);
  }
};

// Where each row's blocks go: the columns of owned vertices (contiguous in a sorted row) to
// A, the others to B; a ghost's to G. Counted in blocks of d × d entries.
struct Layout {
  const Numbering& num;
  const Neighbours& neighbours;
  int d;
  std::vector<PetscInt> diagonal_begin, diagonal_size;  // per row: neighbours in A
  std::vector<PetscInt> a_first, b_first, g_first;      // per row or ghost, then the total

  Layout(const Numbering& n, const Neighbours& lists, int dim)
      : num(n),
        neighbours(lists),
        d(dim),
        diagonal_begin(n.owned),
        diagonal_size(n.owned),
        a_first(n.owned + 1, 0),
        b_first(n.owned + 1, 0),
        g_first(n.num_ghosts() + 1, 0) {
    const Lists& rows = neighbours.rows;
    for (PetscInt r = 0; r < num.owned; ++r) {
      const PetscInt* row = rows.begin(r);
      const PetscInt* end = row + rows.size(r);
      diagonal_begin[r] = std::lower_bound(row, end, num.first) - row;
      diagonal_size[r] =
          std::lower_bound(row, end, num.first + num.owned) - row - diagonal_begin[r];
      a_first[r + 1] = a_first[r] + diagonal_size[r];
      b_first[r + 1] = b_first[r] + rows.size(r) - diagonal_size[r];
    }
    for (PetscInt i = 0; i < num.num_ghosts(); ++i)
      g_first[i + 1] = g_first[i] + neighbours.ghosts.size(i);
  }

  RowPlace place(PetscInt item) const {
    if (item < num.owned)
      return RowPlace{neighbours.rows.begin(item), neighbours.rows.size(item),
                      diagonal_begin[item],        diagonal_begin[item] + diagonal_size[item],
                      d * d * a_first[item],       d * d * b_first[item]};
    const PetscInt i = item - num.owned;
    const PetscInt size = neighbours.ghosts.size(i);
    return RowPlace{neighbours.ghosts.begin(i), size, 0, size, d * d * g_first[i], 0};
  }
};

// row_stride, off_row_stride, diagonal, row_first and off_row_first.
void fill_vertex_entries(const MeshView& view, const Numbering& num, const Layout& layout, int d,
                         AssemblyPattern& p) {
  p.row_stride.resize(view.num_vertices);
  p.off_row_stride.assign(view.num_vertices, 0);
  p.diagonal.assign(d * view.num_vertices, -1);
  p.row_first.resize(view.num_vertices);
  p.off_row_first.assign(view.num_vertices, 0);
  for (PetscInt v = 0; v < view.num_vertices; ++v) {
    const PetscInt i = num.item[v];
    const RowPlace row = layout.place(i);
    p.row_stride[v] = d * (row.diagonal_end - row.diagonal_begin);
    p.row_first[v] = row.first / (d * d);
    if (i >= num.owned) continue;
    p.off_row_first[v] = row.off_first / (d * d);
    p.off_row_stride[v] = d * (row.size - (row.diagonal_end - row.diagonal_begin));
    for (int a = 0; a < d; ++a)
      p.diagonal[d * v + a] = row.entry(num.global[v], d) + a * p.row_stride[v] + a;
  }
}

// block_entry, and the chunks of each block in colour order.
void fill_cell_entries(const MeshView& view, const Numbering& num, const VertexCells& around,
                       const Layout& layout, int d, AssemblyPattern& p) {
  for (const CellBlock& block : view.blocks) {
    const int n = block.nodes();
    std::vector<PetscInt>& entry = p.block_entry.emplace_back(block.vertices.size() * n);
#pragma omp parallel for schedule(static)
    for (PetscInt c = 0; c < block.size(); ++c)
      for (int i = 0; i < n; ++i) {
        const RowPlace row = layout.place(num.item[block.cell(c)[i]]);
        for (int j = 0; j < n; ++j)
          entry[(c * n + i) * n + j] = row.entry(num.global[block.cell(c)[j]], d);
      }

    // Counting sort of the block's chunks by colour.
    const std::vector<PetscInt> colour = colour_block_chunks(around, block);
    const PetscInt chunks = static_cast<PetscInt>(colour.size());
    const PetscInt colours = chunks ? *std::max_element(colour.begin(), colour.end()) + 1 : 0;
    std::vector<PetscInt>& start = p.colour_start.emplace_back(colours + 1, 0);
    for (PetscInt k = 0; k < chunks; ++k) ++start[colour[k] + 1];
    std::partial_sum(start.begin(), start.end(), start.begin());
    std::vector<PetscInt>& order = p.colour_chunks.emplace_back(chunks);
    std::vector<PetscInt> next(start.begin(), start.end() - 1);
    for (PetscInt k = 0; k < chunks; ++k) order[next[colour[k]]++] = k;
  }
}

// Collective. The owners answer each list they received with (A stride, B stride, first
// block in A, first block in B, entry per neighbour), in the order received; then each G
// entry has its place in the owner's A or B.
void make_ghost_exchange(MPI_Comm comm, const Numbering& num, const Neighbours& neighbours,
                         const Layout& layout, int d, AssemblyPattern& p) {
  constexpr int kHeader = 4;
  const Received& in = neighbours.requests;
  const int ranks = static_cast<int>(num.rank_first.size()) - 1;
  std::vector<std::vector<PetscInt>> out(ranks);
  for (int source = 0; source < ranks; ++source)
    for (PetscInt k = in.offset[source]; k < in.offset[source + 1]; k += 2 + in.data[k + 1]) {
      const RowPlace row = layout.place(in.data[k] - num.first);
      std::vector<PetscInt>& to = out[source];
      to.push_back(d * (row.diagonal_end - row.diagonal_begin));
      to.push_back(d * (row.size - (row.diagonal_end - row.diagonal_begin)));
      to.push_back(row.first / (d * d));
      to.push_back(row.off_first / (d * d));
      for (PetscInt j = 0; j < in.data[k + 1]; ++j) to.push_back(row.entry(in.data[k + 2 + j], d));
    }
  const Received answer = send_to_ranks(comm, out);

  constexpr int kUncoupled = static_cast<int>(MatrixLayout::Uncoupled);
  constexpr int kCoupled = static_cast<int>(MatrixLayout::Coupled);
  constexpr int kScalar = static_cast<int>(MatrixLayout::Scalar);
  std::vector<PetscInt> leaves[3][2];  // [layout][to B]
  std::vector<PetscSFNode> roots[3][2];
  std::vector<int> next(answer.offset.begin(), answer.offset.end() - 1);  // per owner
  for (PetscInt i = 0; i < num.num_ghosts(); ++i) {
    const int owner = num.owner(num.global[num.local[num.owned + i]]);
    const PetscInt* reply = answer.data.data() + next[owner];
    const PetscInt size = neighbours.ghosts.size(i);
    next[owner] += kHeader + size;
    for (PetscInt k = 0; k < size; ++k) {
      const bool to_b = reply[kHeader + k] < 0;
      const PetscInt root_block = to_b ? ~reply[kHeader + k] : reply[kHeader + k];
      const PetscInt stride = reply[to_b ? 1 : 0];
      for (int a = 0; a < d; ++a)
        for (int b = 0; b < d; ++b) {
          const PetscInt leaf = d * (d * layout.g_first[i] + k) + a * d * size + b;
          const PetscInt root = root_block + a * stride + b;
          leaves[kCoupled][to_b].push_back(leaf);
          roots[kCoupled][to_b].push_back({owner, root});
          if (a != b) continue;
          leaves[kUncoupled][to_b].push_back(leaf / d);
          roots[kUncoupled][to_b].push_back({owner, root / d});
        }
      // Component 0 alone: block k of the ghost's row at g_first + k, the owner's block at
      // its first block (A or B) + its place in that part (AssemblyPattern::scalar_entry).
      const PetscInt first = reply[to_b ? 3 : 2];
      leaves[kScalar][to_b].push_back(layout.g_first[i] + k);
      roots[kScalar][to_b].push_back({owner, root_block / d - (d - 1) * first});
    }
  }
  for (int l = 0; l < 3; ++l) {
    const std::size_t shrink = l == kCoupled ? 1 : l == kUncoupled ? d : d * d;
    p.ghost_to_diagonal[l] = make_sf(comm, p.diagonal_entries / shrink, leaves[l][0], roots[l][0]);
    p.ghost_to_off_diagonal[l] =
        make_sf(comm, p.off_diagonal_entries / shrink, leaves[l][1], roots[l][1]);
  }
}

}  // namespace

std::pair<std::vector<PetscInt>, std::vector<PetscInt>> layout_csr(const AssemblyPattern& p,
                                                                   MatrixLayout layout, int dim) {
  if (layout == MatrixLayout::Symmetric)
    fail("internal error: the CSR of a matrix of the upper blocks alone");
  const PetscInt owned = static_cast<PetscInt>(p.neighbour_start.size()) - 1;
  if (layout == MatrixLayout::Scalar) return {p.neighbour_start, p.neighbour};
  // Per vertex row: dim rows of `per` columns per neighbour.
  const int per = layout == MatrixLayout::Coupled ? dim : 1;
  std::vector<PetscInt> row_start(dim * owned + 1), column(dim * per * p.neighbour.size());
#pragma omp parallel for schedule(static)
  for (PetscInt r = 0; r < owned; ++r) {
    const PetscInt first = p.neighbour_start[r], size = p.neighbour_start[r + 1] - first;
    for (int a = 0; a < dim; ++a) {
      PetscInt e = dim * per * first + a * per * size;
      row_start[dim * r + a] = e;
      for (PetscInt k = first; k < first + size; ++k)
        for (int b = 0; b < per; ++b) column[e++] = dim * p.neighbour[k] + (per == 1 ? a : b);
    }
  }
  row_start[dim * owned] = static_cast<PetscInt>(column.size());
  return {std::move(row_start), std::move(column)};
}

AssemblyPattern make_assembly_pattern(const MeshView& view, const DofMap& dofs) {
  const int d = dofs.dim();
  MPI_Comm comm = dofs.comm();
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  const Numbering num = number_vertices(view, dofs);
  const VertexCells around(view);
  Neighbours neighbours(num, around);
  if (ranks > 1) neighbours.merge_ghost_lists(comm, num);
  const Layout layout(num, neighbours, d);

  AssemblyPattern p;
  p.diagonal_entries = static_cast<std::size_t>(d * d * layout.a_first.back());
  p.off_diagonal_entries = static_cast<std::size_t>(d * d * layout.b_first.back());
  p.ghost_entries = static_cast<std::size_t>(d * d * layout.g_first.back());
  const PetscInt entries = d * d * neighbours.rows.start.back();
  MPI_Allreduce(&entries, &p.global_entries, 1, MPIU_INT, MPI_SUM, comm);
  fill_vertex_entries(view, num, layout, d, p);
  fill_cell_entries(view, num, around, layout, d, p);
  if (ranks > 1) make_ghost_exchange(comm, num, neighbours, layout, d, p);
  p.neighbour_start = std::move(neighbours.rows.start);
  p.neighbour = std::move(neighbours.rows.value);
  return p;
}

}  // namespace neomesh
