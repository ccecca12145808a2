#include "vae/embedding.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "util/csv_log.h"

namespace vaegail::vae {

namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

std::string header(size_t latent) {
  std::string h = "episode,expert_id,context,achieved_speed,held_out";
  for (size_t j = 0; j < latent; ++j) h += ",mu_" + std::to_string(j);
  for (size_t j = 0; j < latent; ++j) h += ",sigma_" + std::to_string(j);
  return h;
}

double squared_distance(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0;
  for (size_t j = 0; j < a.size(); ++j) s += (a[j] - b[j]) * (a[j] - b[j]);
  return s;
}

}  // namespace

std::string embedding_csv(const std::vector<EmbeddingRow>& rows) {
  const size_t latent = rows.empty() ? 0 : rows[0].mu.size();
  std::string out = header(latent) + "\n";
  for (const auto& r : rows) {
    if (r.mu.size() != latent || r.sigma.size() != latent)
      throw std::invalid_argument("embedding_csv: rows differ in latent size");
    if (r.expert_id.find_first_of(",\n") != std::string::npos)
      throw std::invalid_argument("embedding_csv: expert id '" + r.expert_id + "' holds a comma or newline");
    out += std::to_string(r.episode) + "," + r.expert_id + "," + number(r.context) + "," +
           number(r.achieved_speed) + "," + (r.held_out ? "1" : "0");
    for (double v : r.mu) out += "," + number(v);
    for (double v : r.sigma) out += "," + number(v);
    out += "\n";
  }
  return out;
}

std::vector<EmbeddingRow> parse_embedding_csv(const std::string& text, const std::string& where) {
  std::stringstream in(text);
  std::string line;
  if (!std::getline(in, line)) throw std::invalid_argument(where + ": empty file");
  const auto columns = split_csv_line(line);
  if (columns.size() < 5 || (columns.size() - 5) % 2 != 0 ||
      line != header((columns.size() - 5) / 2))
    throw std::invalid_argument(where + ": line 1: not an embedding header (" + header(1) + "...)");
  const size_t latent = (columns.size() - 5) / 2;
  std::vector<EmbeddingRow> rows;
  for (int n = 2; std::getline(in, line); ++n) {
    if (line.empty()) continue;
    const auto cells = split_csv_line(line);
    const std::string at = where + ": line " + std::to_string(n) + ": ";
    if (cells.size() != columns.size())
      throw std::invalid_argument(at + std::to_string(cells.size()) + " cells, expected " +
                                  std::to_string(columns.size()));
    EmbeddingRow r;
    try {
      size_t used = 0;
      auto num = [&](const std::string& s) {
        const double v = std::stod(s, &used);
        if (used != s.size()) throw std::invalid_argument(s);
        return v;
      };
      r.episode = static_cast<int>(num(cells[0]));
      r.expert_id = cells[1];
      r.context = num(cells[2]);
      r.achieved_speed = num(cells[3]);
      r.held_out = num(cells[4]) != 0.0;
      for (size_t j = 0; j < latent; ++j) r.mu.push_back(num(cells[5 + j]));
      for (size_t j = 0; j < latent; ++j) r.sigma.push_back(num(cells[5 + latent + j]));
    } catch (const std::exception&) {
      throw std::invalid_argument(at + "a cell is not a number");
    }
    rows.push_back(std::move(r));
  }
  return rows;
}

namespace {

// The context most common among the k rows of `pool` nearest to `query` (Euclidean on mu);
// a tied vote goes to the tied context with the nearest member.
double vote(const EmbeddingRow& query, const std::vector<const EmbeddingRow*>& pool, int k) {
  std::vector<std::pair<double, const EmbeddingRow*>> by_distance;
  for (const auto* t : pool) by_distance.push_back({squared_distance(query.mu, t->mu), t});
  k = std::min<int>(k, static_cast<int>(by_distance.size()));
  std::partial_sort(by_distance.begin(), by_distance.begin() + k, by_distance.end(),
                    [](const auto& a, const auto& b) { return a.first < b.first; });
  std::map<double, int> votes;
  for (int i = 0; i < k; ++i) ++votes[by_distance[i].second->context];
  int best_votes = 0;
  for (const auto& [context, n] : votes) best_votes = std::max(best_votes, n);
  for (int i = 0; i < k; ++i)  // nearest first: the first tied winner met wins
    if (votes[by_distance[i].second->context] == best_votes) return by_distance[i].second->context;
  return 0;  // unreachable: k >= 1 and the pool is not empty
}

// Classifies each query against pool_for(query), tallying per target and per expert.
template <typename PoolFor>
KnnResult tally(const std::vector<const EmbeddingRow*>& queries, int k, PoolFor pool_for) {
  if (k < 1) throw std::invalid_argument("knn: k must be >= 1");
  KnnResult result;
  result.k = k;
  std::map<std::string, std::pair<int, int>> per_expert;  // (correct, total)
  for (const auto* q : queries) {
    const auto& pool = pool_for(*q);
    result.k = std::min<int>(result.k, static_cast<int>(pool.size()));
    const bool hit = vote(*q, pool, k) == q->context;
    result.total += 1;
    result.correct += hit;
    auto& target = result.per_target[q->context];
    target.first += hit;
    target.second += 1;
    auto& expert = per_expert[q->expert_id];
    expert.first += hit;
    expert.second += 1;
  }
  result.experts = static_cast<int>(per_expert.size());
  for (const auto& [id, ct] : per_expert) result.experts_majority_correct += 2 * ct.first > ct.second;
  return result;
}

std::vector<const EmbeddingRow*> training_rows(const std::vector<EmbeddingRow>& rows) {
  std::vector<const EmbeddingRow*> train;
  for (const auto& r : rows)
    if (!r.held_out) train.push_back(&r);
  if (train.empty()) throw std::invalid_argument("knn: no training rows (held_out = 0)");
  return train;
}

}  // namespace

KnnResult knn_classify(const std::vector<EmbeddingRow>& rows, int k) {
  const auto train = training_rows(rows);
  std::vector<const EmbeddingRow*> queries;
  for (const auto& r : rows)
    if (r.held_out) queries.push_back(&r);
  if (queries.empty()) throw std::invalid_argument("knn: no held-out rows (held_out = 1) to classify");
  return tally(queries, k, [&](const EmbeddingRow&) -> const auto& { return train; });
}

KnnResult knn_classify_leave_one_expert_out(const std::vector<EmbeddingRow>& rows, int k) {
  const auto train = training_rows(rows);
  std::map<std::string, std::vector<const EmbeddingRow*>> others;  // expert -> the rest
  for (const auto* r : train) others[r->expert_id];
  if (others.size() < 2) throw std::invalid_argument("knn: leaving one expert out needs two training experts");
  for (auto& [id, pool] : others)
    for (const auto* r : train)
      if (r->expert_id != id) pool.push_back(r);
  auto result = tally(train, k, [&](const EmbeddingRow& q) -> const auto& { return others.at(q.expert_id); });
  result.leave_one_expert_out = true;
  return result;
}

std::string format_knn(const KnnResult& r) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "k-NN (k = %d) on %s: %d / %d = %.1f%%%s\n", r.k,
                r.leave_one_expert_out ? "training embeddings, each expert left out in turn" : "held-out embeddings",
                r.correct, r.total, 100.0 * r.accuracy(), r.leave_one_expert_out ? "" : "  (bar: >= 90%)");
  std::string out = buf;
  for (const auto& [context, ct] : r.per_target) {
    std::snprintf(buf, sizeof buf, "  target %+g: %d / %d = %.1f%%\n", context, ct.first, ct.second,
                  100.0 * ct.first / ct.second);
    out += buf;
  }
  std::snprintf(buf, sizeof buf, "  experts with most of their rows correct: %d / %d\n", r.experts_majority_correct,
                r.experts);
  return out + buf;
}

}  // namespace vaegail::vae
