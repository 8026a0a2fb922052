#include "runtime_codes.hpp"

#include <algorithm>
#include <string>
#include <utility>

namespace mocapdb::packing::detail {

namespace {

/// Plain Huffman lengths of the used symbols (ascending symbol order; ties as a binary heap breaks them).
std::vector<int> rt_huffman_depths(const std::vector<std::size_t>& weight) {
    const std::size_t n = weight.size();
    std::vector<int> depth(n, 0);
    if (n == 1) {
        depth[0] = 1;
        return depth;
    }
    std::vector<int> parent(2 * n, -1);
    using Item = std::pair<std::size_t, int>;
    std::vector<Item> heap;
    for (std::size_t i = 0; i < n; ++i) heap.push_back({weight[i], static_cast<int>(i)});
    auto cmp = [](const Item& a, const Item& b) { return a.first > b.first; };
    std::make_heap(heap.begin(), heap.end(), cmp);
    int next = static_cast<int>(n);
    while (heap.size() > 1) {
        std::pop_heap(heap.begin(), heap.end(), cmp);
        const Item a = heap.back();
        heap.pop_back();
        std::pop_heap(heap.begin(), heap.end(), cmp);
        const Item b = heap.back();
        heap.pop_back();
        parent[static_cast<std::size_t>(a.second)] = next;
        parent[static_cast<std::size_t>(b.second)] = next;
        heap.push_back({a.first + b.first, next++});
        std::push_heap(heap.begin(), heap.end(), cmp);
    }
    for (std::size_t i = 0; i < n; ++i)
        for (int v = static_cast<int>(i); parent[static_cast<std::size_t>(v)] >= 0;
             v = parent[static_cast<std::size_t>(v)])
            ++depth[i];
    return depth;
}

}  // namespace

std::vector<std::uint8_t> rt_code_lengths(const std::vector<std::size_t>& counts, int max_length) {
    std::vector<std::uint8_t> lengths(counts.size(), 0);
    std::vector<int> symbols;
    std::vector<std::size_t> weight;
    for (std::size_t s = 0; s < counts.size(); ++s)
        if (counts[s]) {
            symbols.push_back(static_cast<int>(s));
            weight.push_back(counts[s]);
        }
    if (symbols.empty()) return lengths;
    const std::vector<int> depth = rt_huffman_depths(weight);
    std::vector<int> length(symbols.size());
    for (std::size_t i = 0; i < symbols.size(); ++i) length[i] = std::min(depth[i], max_length);
    // Kraft's sum in units of 2^-max_length; lengthen the rarest shorter codes until it is <= 1.
    const std::uint64_t one = std::uint64_t{1} << max_length;
    auto kraft = [&] {
        std::uint64_t k = 0;
        for (int l : length) k += one >> l;
        return k;
    };
    std::vector<std::pair<std::size_t, int>> by_count;  // (count, index), rarest first
    for (std::size_t i = 0; i < symbols.size(); ++i) by_count.push_back({weight[i], static_cast<int>(i)});
    std::sort(by_count.begin(), by_count.end());
    while (kraft() > one)
        for (const auto& [n, i] : by_count)
            if (length[static_cast<std::size_t>(i)] < max_length) {
                ++length[static_cast<std::size_t>(i)];
                break;
            }
    for (std::size_t i = 0; i < symbols.size(); ++i)
        lengths[static_cast<std::size_t>(symbols[i])] = static_cast<std::uint8_t>(length[i]);
    return lengths;
}

std::vector<std::uint32_t> rt_canonical_codes(const std::vector<std::uint8_t>& lengths) {
    std::vector<std::pair<int, int>> order;  // (length, symbol)
    for (std::size_t s = 0; s < lengths.size(); ++s)
        if (lengths[s]) order.push_back({lengths[s], static_cast<int>(s)});
    std::sort(order.begin(), order.end());
    std::vector<std::uint32_t> codes(lengths.size(), 0);
    std::uint32_t c = 0;
    int previous = order.empty() ? 0 : order.front().first;
    for (const auto& [l, s] : order) {
        c <<= (l - previous);
        previous = l;
        codes[static_cast<std::size_t>(s)] = c++;
    }
    return codes;
}

void rt_write_lengths(RtBitWriter& out, const std::vector<std::uint8_t>& lengths, int bits_per_symbol) {
    std::size_t used = 0;
    for (std::uint8_t l : lengths) used += l ? 1 : 0;
    if (used == 0) {
        out.put(0, 2);
        return;
    }
    const std::size_t dense = 4 * lengths.size(),
                      sparse = static_cast<std::size_t>(bits_per_symbol) * (1 + used) + 4 * used;
    if (dense <= sparse) {
        out.put(1, 2);
        for (std::uint8_t l : lengths) out.put(l, 4);
        return;
    }
    out.put(2, 2);
    out.put(used, bits_per_symbol);
    for (std::size_t s = 0; s < lengths.size(); ++s)
        if (lengths[s]) {
            out.put(s, bits_per_symbol);
            out.put(lengths[s], 4);
        }
}

std::vector<std::uint8_t> rt_read_lengths(RtCheckedReader& in, std::size_t alphabet, int bits_per_symbol,
                                          int max_length) {
    std::vector<std::uint8_t> lengths(alphabet, 0);
    const auto mode = in.get(2);
    if (mode == 1) {
        for (auto& l : lengths) l = static_cast<std::uint8_t>(in.get(4));
    } else if (mode == 2) {
        const auto used = static_cast<std::size_t>(in.get(bits_per_symbol));
        for (std::size_t k = 0; k < used; ++k) {
            const auto s = static_cast<std::size_t>(in.get(bits_per_symbol));
            if (s >= alphabet)
                throw Error(std::string(in.what) + ": code symbol " + std::to_string(s) + ", expected below " +
                            std::to_string(alphabet));
            lengths[s] = static_cast<std::uint8_t>(in.get(4));
        }
    } else if (mode != 0) {
        throw Error(std::string(in.what) + ": code table mode 3, expected 0, 1 or 2");
    }
    std::uint64_t kraft = 0;
    const std::uint64_t one = std::uint64_t{1} << max_length;
    for (std::uint8_t l : lengths) {
        if (l > max_length)
            throw Error(std::string(in.what) + ": code length " + std::to_string(l) + ", expected at most " +
                        std::to_string(max_length));
        if (l) kraft += one >> l;
    }
    if (kraft > one) throw Error(std::string(in.what) + ": code lengths over-subscribe the code (Kraft's sum above 1)");
    return lengths;
}

RtSlowCode::RtSlowCode(const std::vector<std::uint8_t>& lengths) : first_(17, 0), count_(17, 0), index_(17, 0) {
    const std::vector<std::uint32_t> codes = rt_canonical_codes(lengths);
    std::vector<std::pair<int, int>> order;
    for (std::size_t s = 0; s < lengths.size(); ++s)
        if (lengths[s]) order.push_back({lengths[s], static_cast<int>(s)});
    std::sort(order.begin(), order.end());
    for (std::size_t i = 0; i < order.size(); ++i) {
        const auto [l, s] = order[i];
        const auto L = static_cast<std::size_t>(l);
        if (count_[L] == 0) {
            first_[L] = codes[static_cast<std::size_t>(s)];
            index_[L] = static_cast<std::uint32_t>(i);
        }
        ++count_[L];
        sorted_.push_back(s);
    }
}

int RtSlowCode::read(RtCheckedReader& in) const {
    std::uint32_t v = 0;
    for (std::size_t l = 1; l <= 16; ++l) {
        v = (v << 1) | static_cast<std::uint32_t>(in.get(1));
        if (count_[l] && v >= first_[l] && v - first_[l] < count_[l]) return sorted_[index_[l] + (v - first_[l])];
    }
    throw Error(std::string(in.what) + ": bits that are no code of the table");
}

}  // namespace mocapdb::packing::detail
