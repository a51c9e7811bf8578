#include "mesh/partition_facets.hpp"

#include <algorithm>
#include <array>
#include <numeric>
#include <tuple>

#include "core/petsc.hpp"
#include "mesh/cell_type.hpp"

namespace neomesh {

namespace {

static_assert(std::tuple_size_v<decltype(CellFacts::facets)> == PartitionFacets::kMaxFacets);

using Key = std::array<std::int64_t, 4>;  // sorted input vertex numbers, then -1

// What a rank sends to the rank that pairs a facet: its key, the sender's index of the facet
// and the input number of the cell it belongs to.
constexpr int kRequestSize = 6;
// What the pairing rank answers: the sender's index, the rank and cell across.
constexpr int kReplySize = 3;

std::uint64_t mix(std::uint64_t h) {  // splitmix64's finalizer: the same on every rank
  h ^= h >> 30;
  h *= 0xbf58476d1ce4e5b9ULL;
  h ^= h >> 27;
  h *= 0x94d049bb133111ebULL;
  return h ^ (h >> 31);
}

int pairing_rank(const Key& key, int size) {
  std::uint64_t h = 0;
  for (std::int64_t v : key) h = mix(h ^ static_cast<std::uint64_t>(v));
  return static_cast<int>(h % static_cast<std::uint64_t>(size));
}

std::vector<int> offsets_of(const std::vector<int>& counts) {
  std::vector<int> offsets(counts.size() + 1, 0);
  std::partial_sum(counts.begin(), counts.end(), offsets.begin() + 1);
  return offsets;
}

// Sends `send[r]` to every rank r; returns what each rank sent here, by rank.
std::vector<std::vector<std::int64_t>> all_to_all(
    MPI_Comm comm, const std::vector<std::vector<std::int64_t>>& send) {
  const int size = mpi_size(comm);
  std::vector<int> send_counts(size), recv_counts(size);
  for (int r = 0; r < size; ++r) send_counts[r] = static_cast<int>(send[r].size());
  MPI_Alltoall(send_counts.data(), 1, MPI_INT, recv_counts.data(), 1, MPI_INT, comm);
  const std::vector<int> send_offsets = offsets_of(send_counts),
                         recv_offsets = offsets_of(recv_counts);
  std::vector<std::int64_t> out(send_offsets[size]), in(recv_offsets[size]);
  for (int r = 0; r < size; ++r)
    std::copy(send[r].begin(), send[r].end(), out.begin() + send_offsets[r]);
  MPI_Alltoallv(out.data(), send_counts.data(), send_offsets.data(), MPI_INT64_T, in.data(),
                recv_counts.data(), recv_offsets.data(), MPI_INT64_T, comm);
  std::vector<std::vector<std::int64_t>> received(size);
  for (int r = 0; r < size; ++r)
    received[r].assign(in.begin() + recv_offsets[r], in.begin() + recv_offsets[r + 1]);
  return received;
}

}  // namespace

PartitionFacets::PartitionFacets(const MeshView& view, MPI_Comm comm,
                                 std::span<const std::uint8_t> open)
    : comm_(comm) {
  const int size = mpi_size(comm);
  send_counts_.assign(size, 0);
  send_offsets_.assign(size + 1, 0);
  if (size == 1) return;

  // The open facets' keys, sent to the ranks that pair them.
  std::vector<Key> keys;
  std::vector<Facet> candidates;
  std::vector<std::vector<std::int64_t>> requests(size);
  for (const CellBlock& block : view.blocks) {
    const CellFacts& cell_facts = facts(block.type);
    for (PetscInt c = 0; c < block.size(); ++c) {
      const PetscInt cell = block.first_cell + c;
      for (int f = 0; f < cell_facts.num_facets; ++f) {
        if (!open[cell * kMaxFacets + f]) continue;
        const FacetVertices& facet = cell_facts.facets[f];
        Key key = {-1, -1, -1, -1};
        for (int k = 0; k < facet.size; ++k)
          key[k] = view.input_vertex[block.cell(c)[facet.vertices[k]]];
        sort_facet_key(key, facet.size);
        std::vector<std::int64_t>& to = requests[pairing_rank(key, size)];
        to.insert(to.end(), key.begin(), key.end());
        to.push_back(static_cast<std::int64_t>(keys.size()));
        to.push_back(view.global_cell[cell]);
        keys.push_back(key);
        candidates.push_back({cell, f, -1, -1});
      }
    }
  }

  // Pairing: the two requests with the same key come from the ranks on either side.
  const std::vector<std::vector<std::int64_t>> received = all_to_all(comm, requests);
  struct Request {
    Key key;
    int rank;
    std::int64_t index, cell;
  };
  std::vector<Request> all;
  for (int r = 0; r < size; ++r)
    for (std::size_t i = 0; i < received[r].size(); i += kRequestSize) {
      const std::int64_t* q = received[r].data() + i;
      all.push_back({{q[0], q[1], q[2], q[3]}, r, q[4], q[5]});
    }
  std::sort(all.begin(), all.end(), [](const Request& a, const Request& b) {
    return std::tie(a.key, a.rank) < std::tie(b.key, b.rank);
  });
  std::vector<std::vector<std::int64_t>> replies(size);
  for (std::size_t i = 0; i + 1 < all.size(); ++i) {
    const Request &a = all[i], &b = all[i + 1];
    if (a.key != b.key || a.rank == b.rank) continue;
    replies[a.rank].insert(replies[a.rank].end(), {a.index, b.rank, b.cell});
    replies[b.rank].insert(replies[b.rank].end(), {b.index, a.rank, a.cell});
    ++i;
  }

  // The shared facets, grouped by rank and ordered by key: the same order on both sides.
  std::vector<std::size_t> shared;
  for (const std::vector<std::int64_t>& from : all_to_all(comm, replies))
    for (std::size_t i = 0; i < from.size(); i += kReplySize) {
      Facet& facet = candidates[from[i]];
      facet.rank = static_cast<int>(from[i + 1]);
      facet.remote_cell = static_cast<PetscInt>(from[i + 2]);
      shared.push_back(from[i]);
    }
  std::sort(shared.begin(), shared.end(), [&](std::size_t a, std::size_t b) {
    return std::tie(candidates[a].rank, keys[a]) < std::tie(candidates[b].rank, keys[b]);
  });
  for (std::size_t i : shared) {
    facets_.push_back(candidates[i]);
    ++send_counts_[candidates[i].rank];
  }
  std::partial_sum(send_counts_.begin(), send_counts_.end(), send_offsets_.begin() + 1);
}

std::vector<std::uint8_t> PartitionFacets::exchange(std::span<const std::uint8_t> values) const {
  std::vector<std::uint8_t> out(facets_.size());
  if (mpi_size(comm_) == 1) return out;
  MPI_Alltoallv(values.data(), send_counts_.data(), send_offsets_.data(), MPI_UINT8_T, out.data(),
                send_counts_.data(), send_offsets_.data(), MPI_UINT8_T, comm_);
  return out;
}

}  // namespace neomesh
