#pragma once
// The sorts behind search::Grid, and permute_records: templates over the key type, so they
// live in this header (a caller needs OpenMP to build them).

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <utility>
#include <vector>

#include <omp.h>

#include <pc/core/cloud.h>

namespace pc {

/// LSD radix sort of n (key, index) pairs, 12 bits per pass, skipping passes where all digits
/// agree. Keys are 32-bit when the cell key fits (nearly always): half the bytes to move and hold.
/// `k2` and `i2` are scratch of n entries each; the sorted pairs end in either array of each
/// pair, which is returned. Each pass runs on two threads (each counts and moves its half of the
/// input; its elements go after the first half's within every digit): stable, so the result is
/// the serial sort's.
template <class Key>
std::pair<Key*, std::uint32_t*> radix_sort_pairs(
    Key* keys, std::uint32_t* idx, Key* k2, std::uint32_t* i2, std::size_t n) {
    Key all_or = 0, all_and = static_cast<Key>(~Key{0});
    for (std::size_t i = 0; i < n; ++i) {
        all_or |= keys[i];
        all_and &= keys[i];
    }
    const Key varying = all_or ^ all_and;
    constexpr std::size_t kDigits = 4096;
    const int threads = n >= (std::size_t{1} << 16) ? 2 : 1;  // small inputs: not worth a thread
    std::vector<std::size_t> count(kDigits * static_cast<std::size_t>(threads));
    for (int shift = 0; shift < static_cast<int>(8 * sizeof(Key)); shift += 12) {
        if (((varying >> shift) & 0xfff) == 0) {
            continue;
        }
        std::fill(count.begin(), count.end(), 0);
#pragma omp parallel num_threads(threads)
        {
            // The team may be smaller than asked (nested in another parallel region, a limit).
            const auto parts = static_cast<std::size_t>(omp_get_num_threads());
            const auto part = static_cast<std::size_t>(omp_get_thread_num());
            const std::size_t from = n * part / parts;
            const std::size_t to = n * (part + 1) / parts;
            std::size_t* mine = &count[kDigits * part];
            for (std::size_t i = from; i < to; ++i) {
                ++mine[(keys[i] >> shift) & 0xfff];
            }
#pragma omp barrier
#pragma omp single
            {
                // Digit-major, part-minor starting offsets.
                std::size_t at = 0;
                for (std::size_t d = 0; d < kDigits; ++d) {
                    for (std::size_t p = 0; p < parts; ++p) {
                        const std::size_t c = count[kDigits * p + d];
                        count[kDigits * p + d] = at;
                        at += c;
                    }
                }
            }
            for (std::size_t i = from; i < to; ++i) {
                const std::size_t at = mine[(keys[i] >> shift) & 0xfff]++;
                k2[at] = keys[i];
                i2[at] = idx[i];
            }
        }
        std::swap(keys, k2);
        std::swap(idx, i2);
    }
    return {keys, idx};
}

/// A 32-bit word that may alias a float: the sort's keys and scratch live in the coordinates'
/// storage until the coordinates are written there.
using Word = std::uint32_t __attribute__((may_alias));

namespace detail {

/// Swaps two records of `words` 4-byte words (kWords when fixed at compile time, else 0).
template <std::size_t kWords>
inline void swap_words(Word* a, Word* b, std::size_t words) {
    for (std::size_t w = 0; w < (kWords != 0 ? kWords : words); ++w) {
        const std::uint32_t t = a[w];
        a[w] = b[w];
        b[w] = t;
    }
}

/// dest[i]: where the record at lo + i of a bucket of m (>= 2) goes. Distinct keys spanning m
/// values (untagged: original indices) are placed directly; other keys (repeated cell keys may
/// span m values too) by an LSD radix sort of their positions over the key bits that vary.
template <class Key, bool kTagged>
void leaf_destinations(const Key* keys,
                       std::size_t lo,
                       std::size_t m,
                       std::vector<std::uint32_t>& dest) {
    thread_local std::vector<std::uint32_t> pos, pos2;
    const std::size_t hi = lo + m;
    dest.resize(m);
    Key kmin = keys[lo], kmax = keys[lo], varying = 0;
    for (std::size_t i = lo; i < hi; ++i) {
        kmin = std::min(kmin, keys[i]);
        kmax = std::max(kmax, keys[i]);
        varying |= keys[i] ^ keys[lo];
    }
    if (!kTagged && kmax - kmin == m - 1) {
        for (std::size_t i = 0; i < m; ++i) {
            dest[i] = static_cast<std::uint32_t>(keys[lo + i] - kmin);
        }
    } else {
        pos.resize(m);
        pos2.resize(m);
        for (std::size_t i = 0; i < m; ++i) {
            pos[i] = static_cast<std::uint32_t>(i);
        }
        for (int shift = 0; shift < static_cast<int>(std::bit_width(varying)); shift += 8) {
            std::array<std::uint32_t, 257> count{};
            for (std::size_t i = 0; i < m; ++i) {
                ++count[((keys[lo + i] >> shift) & 0xff) + 1];
            }
            for (std::size_t d = 1; d < 257; ++d) {
                count[d] += count[d - 1];
            }
            for (std::size_t i = 0; i < m; ++i) {
                const std::uint32_t p = pos[i];
                pos2[count[(keys[lo + p] >> shift) & 0xff]++] = p;
            }
            pos.swap(pos2);
        }
        for (std::size_t i = 0; i < m; ++i) {
            dest[pos[i]] = static_cast<std::uint32_t>(i);
        }
    }
}

/// Moves the records lo .. lo + dest.size() - 1 (with their keys and tags) to lo + dest[i],
/// walking each cycle of the permutation once; dest is left as the identity.
template <class Key, std::size_t kWords, bool kTagged>
void apply_cycles(std::uint8_t* rec,
                  std::size_t step,
                  Key* keys,
                  std::uint32_t* tags,
                  std::size_t lo,
                  std::vector<std::uint32_t>& dest) {
    const std::size_t words = kWords != 0 ? kWords : step / sizeof(Word);
    const std::size_t m = dest.size();
    // Each cycle of the permutation walked once: the record in hand goes to its place and
    // the one there is taken up; dest[j] = j marks a place done.
    std::array<std::uint32_t, 64> held{};  // step is at most 256 here
    for (std::size_t i = 0; i < m; ++i) {
        if (dest[i] == i) {
            continue;
        }
        const Word* from = reinterpret_cast<const Word*>(rec + (lo + i) * step);
        std::copy(from, from + words, held.begin());
        Key held_key = keys[lo + i];
        std::uint32_t held_tag = kTagged ? tags[lo + i] : 0;
        std::size_t j = dest[i];
        dest[i] = static_cast<std::uint32_t>(i);
        while (true) {
            swap_words<kWords>(reinterpret_cast<Word*>(rec + (lo + j) * step), held.data(), words);
            std::swap(held_key, keys[lo + j]);
            if constexpr (kTagged) {
                std::swap(held_tag, tags[lo + j]);
            }
            if (j == i) {
                break;
            }
            const std::size_t k = dest[j];
            dest[j] = static_cast<std::uint32_t>(j);
            j = k;
        }
    }
}

/// Sorts n records of `step` bytes (a multiple of 4) at `rec` in place by keys[i], carrying keys
/// and, when kTagged, tags along. Untagged, the keys must be distinct (the records' original
/// indices: putting them back). Not stable. American flag sort (in-place MSD radix, 8 bits a
/// level) until a bucket fits in the cache; a bucket's (key, position) pairs are then sorted
/// aside and the records moved once each by walking the permutation's cycles. Every move thus
/// lands at one of 256 advancing places or inside a cached bucket: applying the whole
/// permutation by its cycles instead took 0.4 s for 4M points here (20 ms for 1M, which fit in
/// the cache). Buckets of the first level are sorted on two threads.
template <class Key, std::size_t kWords, bool kTagged>
void flag_sort_impl(
    std::uint8_t* rec, std::size_t step, Key* keys, std::uint32_t* tags, std::size_t n) {
    const std::size_t words = kWords != 0 ? kWords : step / sizeof(Word);
    const auto swap = [&](std::size_t i, std::size_t j) {
        swap_words<kWords>(reinterpret_cast<Word*>(rec + i * step),
                           reinterpret_cast<Word*>(rec + j * step), words);
        std::swap(keys[i], keys[j]);
        if constexpr (kTagged) {
            std::swap(tags[i], tags[j]);
        }
    };
    // A bucket of at most kLeaf records (about 200 KiB for x y z only, and 200 KiB of positions)
    // is sorted aside, then permuted.
    constexpr std::size_t kLeaf = 16384;
    const auto leaf = [&](std::size_t lo, std::size_t hi) {
        thread_local std::vector<std::uint32_t> dest;
        if (hi - lo < 2) {
            return;  // nothing to move (and keys[lo] may be past the end)
        }
        dest.resize(hi - lo);
        leaf_destinations<Key, kTagged>(keys, lo, hi - lo, dest);
        apply_cycles<Key, kWords, kTagged>(rec, step, keys, tags, lo, dest);
    };
    // The digit of key k at `shift`: bits shift .. shift + 7 (a negative shift: the lowest bits,
    // moved up).
    const auto digit = [](Key k, int shift) {
        return static_cast<unsigned>((shift >= 0 ? k >> shift : k << -shift) & 0xff);
    };
    const auto sort = [&](auto& self, std::size_t lo, std::size_t hi, int shift,
                          bool parallel) -> void {
        if (hi - lo <= kLeaf && step <= 256) {
            leaf(lo, hi);
            return;
        }
        std::array<std::size_t, 256> head{}, end{};
        for (std::size_t i = lo; i < hi; ++i) {
            ++end[digit(keys[i], shift)];
        }
        std::size_t at = lo;
        for (unsigned d = 0; d < 256; ++d) {
            head[d] = at;
            at += end[d];
            end[d] = at;
        }
        const std::array<std::size_t, 256> begin = head;
        for (unsigned d = 0; d < 256; ++d) {
            // Four records at a time, their digits read first: the four moves are independent,
            // so their cache misses overlap (one at a time, each waited for the last: 1.5x
            // slower). Positions below head[d] hold bucket d's records; a record swapped in is
            // looked at in a later round. Each target head[e] lies outside [head[d], end[d])
            // unless e == d, and then at or below the record moved: the later digits stay valid.
            while (end[d] - head[d] >= 4) {
                const std::size_t i = head[d];
                const unsigned e0 = digit(keys[i], shift), e1 = digit(keys[i + 1], shift);
                const unsigned e2 = digit(keys[i + 2], shift), e3 = digit(keys[i + 3], shift);
                swap(i, head[e0]++);
                swap(i + 1, head[e1]++);
                swap(i + 2, head[e2]++);
                swap(i + 3, head[e3]++);
            }
            while (head[d] < end[d]) {
                const std::size_t i = head[d];
                for (unsigned e = digit(keys[i], shift); e != d; e = digit(keys[i], shift)) {
                    swap(i, head[e]++);
                }
                ++head[d];
            }
        }
        if (shift <= 0) {
            return;  // the last digit: each bucket holds one key
        }
        // Buckets wider than a leaf recurse (a few hundred calls at most for 4M points): the
        // one-thread team that `if` makes below the first level costs nothing that shows.
#pragma omp parallel for schedule(dynamic, 1) num_threads(2) if (parallel)
        for (int d = 0; d < 256; ++d) {
            if (end[d] - begin[d] > 1) {
                self(self, begin[d], end[d], shift - 8, false);
            }
        }
    };
    Key all = 0;
    for (std::size_t i = 0; i < n; ++i) {
        all |= keys[i];
    }
    const int bits = static_cast<int>(std::bit_width(all));
    if (bits > 0) {
        sort(sort, 0, n, bits - 8, n >= (std::size_t{1} << 16));
    }
}

}  // namespace detail

/// Sorts n records of `step` bytes (a multiple of 4) at `rec` in place by keys[i], carrying the
/// keys and, unless null, `tags` along; with tags null the keys must be distinct (e.g. original
/// indices, to put records back). Not stable. American flag sort until a bucket fits in the
/// cache (detail::flag_sort_impl), the record size fixed for the common layouts (x y z, + 1, 2
/// or 5 fields).
template <class Key>
void flag_sort(std::uint8_t* rec, std::size_t step, Key* keys, std::uint32_t* tags, std::size_t n) {
    const auto run = [&]<std::size_t kWords>() {
        if (tags != nullptr) {
            detail::flag_sort_impl<Key, kWords, true>(rec, step, keys, tags, n);
        } else {
            detail::flag_sort_impl<Key, kWords, false>(rec, step, keys, tags, n);
        }
    };
    switch (step) {
        case 12:
            run.template operator()<3>();
            break;
        case 16:
            run.template operator()<4>();
            break;
        case 20:
            run.template operator()<5>();
            break;
        case 32:
            run.template operator()<8>();
            break;
        default:
            run.template operator()<0>();
            break;
    }
}

/// Moves record i of the to.size() records of `stride` bytes (a multiple of 4) at `base` to place
/// to[i] in place (`to`: a permutation of 0..size-1; it is left sorted): e.g. the elements of an
/// array of 4-byte values. std::logic_error on a stride that is not whole words.
inline void permute_records(void* base, std::size_t stride, std::span<std::uint32_t> to) {
    if (stride == 0 || stride % sizeof(std::uint32_t) != 0) {
        throw std::logic_error("permute_records: records of whole 4-byte words");
    }
    flag_sort<std::uint32_t>(static_cast<std::uint8_t*>(base), stride, to.data(), nullptr,
                             to.size());
}

/// The same for the records of a cloud (std::logic_error unless `to` has one place a record).
inline void permute_records(XyzRecords& records, std::span<std::uint32_t> to) {
    if (to.size() != records.size) {
        throw std::logic_error("permute_records: one place per record");
    }
    permute_records(records.base, records.stride, to);
}

}  // namespace pc
