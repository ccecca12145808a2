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
    // context and achieved speed may be nan (a task without them); a nan in z would silently
    // drop out of every distance comparison.
    for (size_t j = 0; j < latent; ++j)
      if (!std::isfinite(r.mu[j]) || !std::isfinite(r.sigma[j]))
        throw std::invalid_argument(at + (std::isfinite(r.mu[j]) ? "sigma_" : "mu_") + std::to_string(j) +
                                    " is not finite");
    rows.push_back(std::move(r));
  }
  return rows;
}

namespace {

// The k rows of `pool` nearest to `query` (Euclidean on mu), nearest first.
std::vector<const EmbeddingRow*> nearest(const EmbeddingRow& query, const std::vector<const EmbeddingRow*>& pool,
                                         int k) {
  std::vector<std::pair<double, const EmbeddingRow*>> by_distance;
  for (const auto* t : pool) by_distance.push_back({squared_distance(query.mu, t->mu), t});
  k = std::min<int>(k, static_cast<int>(by_distance.size()));
  std::partial_sort(by_distance.begin(), by_distance.begin() + k, by_distance.end(),
                    [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<const EmbeddingRow*> out;
  for (int i = 0; i < k; ++i) out.push_back(by_distance[i].second);
  return out;
}

// The context most common among `neighbours` (nearest first); a tied vote goes to the tied
// context with the nearest member.
double vote(const std::vector<const EmbeddingRow*>& neighbours) {
  std::map<double, int> votes;
  for (const auto* n : neighbours) ++votes[n->context];
  int best_votes = 0;
  for (const auto& [context, n] : votes) best_votes = std::max(best_votes, n);
  for (const auto* n : neighbours)  // nearest first: the first tied winner met wins
    if (votes[n->context] == best_votes) return n->context;
  return 0;  // unreachable: k >= 1 and the pool is not empty
}

// Classifies each query against pool_for(query), tallying per target and per expert.
template <typename PoolFor>
KnnResult tally(const std::vector<const EmbeddingRow*>& queries, int k, PoolFor pool_for) {
  if (k < 1) throw std::invalid_argument("knn: k must be >= 1");
  KnnResult result;
  result.k = k;
  for (const auto* q : queries) {
    const auto& pool = pool_for(*q);
    result.k = std::min<int>(result.k, static_cast<int>(pool.size()));
    const auto neighbours = nearest(*q, pool, k);
    const bool hit = vote(neighbours) == q->context;
    result.total += 1;
    result.correct += hit;
    auto& target = result.per_target[q->context];
    target.first += hit;
    target.second += 1;
    auto& expert = result.per_expert[q->expert_id];
    expert.contexts.insert(q->context);
    expert.correct += hit;
    expert.total += 1;
    for (const auto* n : neighbours) ++expert.neighbours[n->expert_id];
  }
  result.experts = static_cast<int>(result.per_expert.size());
  for (const auto& [id, e] : result.per_expert) result.experts_majority_correct += 2 * e.correct > e.total;
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

namespace {

// "  expert ID (target T): C / N; nearest: A 40, B 12, C 8" with the three most frequent
// neighbours; "targets -1/0/1" for a context-conditioned expert.
std::string expert_line(const std::string& id, const ExpertVote& e) {
  std::vector<std::pair<int, std::string>> by_count;
  for (const auto& [neighbour, n] : e.neighbours) by_count.push_back({-n, neighbour});
  std::sort(by_count.begin(), by_count.end());
  std::string targets;
  for (double c : e.contexts) targets += (targets.empty() ? "" : "/") + number(c);
  std::string line = "  expert " + id + (e.contexts.size() > 1 ? " (targets " : " (target ") + targets +
                     "): " + std::to_string(e.correct) + " / " + std::to_string(e.total) + "; nearest:";
  for (size_t i = 0; i < std::min<size_t>(3, by_count.size()); ++i)
    line += (i ? ", " : " ") + by_count[i].second + " " + std::to_string(-by_count[i].first);
  return line + "\n";
}

}  // namespace

std::string format_knn(const KnnResult& r, bool by_expert) {
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
  out += buf;
  if (by_expert)
    for (const auto& [id, e] : r.per_expert) out += expert_line(id, e);
  return out;
}

}  // namespace vaegail::vae
