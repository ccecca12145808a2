#include "eval/embedding.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <sstream>
#include <stdexcept>

#include "util/csv_log.h"

namespace vaegail::eval {

namespace {

std::string exact_number(double v) { return fmt::format("{:.9g}", v); }

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
    out += std::to_string(r.episode) + "," + r.expert_id + "," + exact_number(r.context) + "," +
           exact_number(r.achieved_speed) + "," + (r.held_out ? "1" : "0");
    for (double v : r.mu) out += "," + exact_number(v);
    for (double v : r.sigma) out += "," + exact_number(v);
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

// A query's classification: the target it gets, the rows it was voted by (k-NN) and its
// read-out (linear).
struct Prediction {
  double context = 0;
  std::vector<const EmbeddingRow*> neighbours;
  double readout = 0;
};

// Classifies each query, tallying per target and per expert.
template <typename Classify>
TargetClassification tally(const std::vector<const EmbeddingRow*>& queries, Classify classify) {
  TargetClassification result;
  for (const auto* q : queries) {
    const Prediction p = classify(*q);
    const bool hit = p.context == q->context;
    result.total += 1;
    result.correct += hit;
    auto& target = result.per_target[q->context];
    target.first += hit;
    target.second += 1;
    auto& expert = result.per_expert[q->expert_id];
    expert.contexts.insert(q->context);
    expert.correct += hit;
    expert.total += 1;
    expert.readout_sum += p.readout;
    for (const auto* n : p.neighbours) ++expert.neighbours[n->expert_id];
  }
  result.experts = static_cast<int>(result.per_expert.size());
  for (const auto& [id, e] : result.per_expert) result.experts_majority_correct += 2 * e.correct > e.total;
  return result;
}

// Each query against pool_for(query) by the k-NN vote.
template <typename PoolFor>
TargetClassification knn_tally(const std::vector<const EmbeddingRow*>& queries, int k, PoolFor pool_for) {
  if (k < 1) throw std::invalid_argument("knn: k must be >= 1");
  int smallest_k = k;
  auto result = tally(queries, [&](const EmbeddingRow& q) {
    const auto& pool = pool_for(q);
    smallest_k = std::min<int>(smallest_k, static_cast<int>(pool.size()));
    auto neighbours = nearest(q, pool, k);
    return Prediction{vote(neighbours), std::move(neighbours), 0.0};
  });
  result.k = smallest_k;
  return result;
}

// Sums over rows of x xᵀ and x·target, x = [mu, 1]: the normal equations of least squares from
// x to the target. A pool's sums are its experts' sums added, so leaving one expert out is a
// subtraction rather than a pass over the rows.
struct NormalEquations {
  size_t n = 0;
  std::vector<double> xx, xy;  // n x n row-major, n
  std::map<double, int> targets;  // target -> rows

  void add(const EmbeddingRow& r) {
    if (n == 0) {
      n = r.mu.size() + 1;
      xx.assign(n * n, 0.0);
      xy.assign(n, 0.0);
    }
    for (size_t i = 0; i < n; ++i) {
      const double xi = i + 1 < n ? r.mu[i] : 1.0;
      for (size_t j = 0; j < n; ++j) xx[i * n + j] += xi * (j + 1 < n ? r.mu[j] : 1.0);
      xy[i] += xi * r.context;
    }
    ++targets[r.context];
  }
  NormalEquations minus(const NormalEquations& o) const {
    NormalEquations d = *this;
    for (size_t i = 0; i < xx.size(); ++i) d.xx[i] -= o.xx[i];
    for (size_t i = 0; i < xy.size(); ++i) d.xy[i] -= o.xy[i];
    for (const auto& [t, rows] : o.targets)
      if ((d.targets[t] -= rows) == 0) d.targets.erase(t);
    return d;
  }
};

// A fitted read-out: the weights (bias last) and the targets its rows had, to snap to.
struct Readout {
  std::vector<double> w;
  std::vector<double> targets;

  Prediction operator()(const EmbeddingRow& q) const {
    double value = w.back();
    for (size_t j = 0; j + 1 < w.size(); ++j) value += w[j] * q.mu[j];
    double best = targets.front();
    for (double t : targets)
      if (std::abs(t - value) < std::abs(best - value)) best = t;
    return Prediction{best, {}, value};
  }
};

// Ridge regression: (XᵀX + ridge·I on the weights, not the bias) w = Xᵀy, by Gauss-Jordan
// elimination with partial pivoting.
Readout fit_readout(const NormalEquations& e, double ridge) {
  const size_t n = e.n;
  std::vector<std::vector<double>> a(n, std::vector<double>(n + 1));
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = 0; j < n; ++j) a[i][j] = e.xx[i * n + j] + (i == j && i + 1 < n ? ridge : 0.0);
    a[i][n] = e.xy[i];
  }
  for (size_t c = 0; c < n; ++c) {
    size_t pivot = c;
    for (size_t r = c + 1; r < n; ++r)
      if (std::abs(a[r][c]) > std::abs(a[pivot][c])) pivot = r;
    if (std::abs(a[pivot][c]) < 1e-12) throw std::invalid_argument("linear read-out: singular least-squares system");
    std::swap(a[c], a[pivot]);
    for (size_t r = 0; r < n; ++r) {
      if (r == c) continue;
      const double f = a[r][c] / a[c][c];
      for (size_t j = c; j <= n; ++j) a[r][j] -= f * a[c][j];
    }
  }
  Readout out;
  for (size_t i = 0; i < n; ++i) out.w.push_back(a[i][n] / a[i][i]);
  for (const auto& [t, rows] : e.targets) out.targets.push_back(t);
  return out;
}

// Training rows grouped by expert, each group with its normal equations.
struct ExpertRows {
  std::vector<const EmbeddingRow*> rows;
  NormalEquations sums;
};

// The ridge, from 1e-6 to 100 by decades, under which the read-out classifies most rows right
// when each of `experts` is read by a fit over the others (their sums: `total`); a tie goes to
// the larger ridge, the smoother fit. Chosen on training experts alone: a latent dimension that
// barely varies over them can take a large weight in a plain fit, which then misreads an
// unseen expert that varies along it.
double choose_ridge(const std::map<std::string, ExpertRows>& experts, const NormalEquations& total,
                    const std::string& excluded) {
  double best_ridge = 0;
  int best = -1;
  for (double ridge = 1e-6; ridge < 1e3; ridge *= 10) {
    int correct = 0;
    for (const auto& [id, e] : experts) {
      if (id == excluded) continue;
      const NormalEquations others = total.minus(e.sums);
      if (others.targets.empty()) continue;
      const Readout readout = fit_readout(others, ridge);
      for (const auto* r : e.rows) correct += readout(*r).context == r->context;
    }
    if (correct >= best) best = correct, best_ridge = ridge;
  }
  return best_ridge;
}

std::map<std::string, ExpertRows> rows_by_expert(const std::vector<const EmbeddingRow*>& train,
                                                  NormalEquations& total) {
  std::map<std::string, ExpertRows> experts;
  for (const auto* r : train) {
    experts[r->expert_id].rows.push_back(r);
    experts[r->expert_id].sums.add(*r);
    total.add(*r);
  }
  if (experts.size() < 2) throw std::invalid_argument("linear read-out: choosing its ridge needs two training experts");
  return experts;
}

std::vector<const EmbeddingRow*> training_rows(const std::vector<EmbeddingRow>& rows) {
  std::vector<const EmbeddingRow*> train;
  for (const auto& r : rows)
    if (!r.held_out) train.push_back(&r);
  if (train.empty()) throw std::invalid_argument("knn: no training rows (held_out = 0)");
  return train;
}

std::vector<const EmbeddingRow*> held_out_rows(const std::vector<EmbeddingRow>& rows) {
  std::vector<const EmbeddingRow*> queries;
  for (const auto& r : rows)
    if (r.held_out) queries.push_back(&r);
  if (queries.empty()) throw std::invalid_argument("knn: no held-out rows (held_out = 1) to classify");
  return queries;
}

// Training expert -> the training rows of every other expert.
std::map<std::string, std::vector<const EmbeddingRow*>> other_experts_rows(
    const std::vector<const EmbeddingRow*>& train) {
  std::map<std::string, std::vector<const EmbeddingRow*>> others;
  for (const auto* r : train) others[r->expert_id];
  if (others.size() < 2) throw std::invalid_argument("knn: leaving one expert out needs two training experts");
  for (auto& [id, pool] : others)
    for (const auto* r : train)
      if (r->expert_id != id) pool.push_back(r);
  return others;
}

}  // namespace

TargetClassification knn_classify(const std::vector<EmbeddingRow>& rows, int k) {
  const auto train = training_rows(rows);
  return knn_tally(held_out_rows(rows), k, [&](const EmbeddingRow&) -> const auto& { return train; });
}

TargetClassification knn_classify_leave_one_expert_out(const std::vector<EmbeddingRow>& rows, int k) {
  const auto train = training_rows(rows);
  const auto others = other_experts_rows(train);
  auto result = knn_tally(train, k, [&](const EmbeddingRow& q) -> const auto& { return others.at(q.expert_id); });
  result.leave_one_expert_out = true;
  return result;
}

TargetClassification linear_classify(const std::vector<EmbeddingRow>& rows) {
  NormalEquations total;
  const auto experts = rows_by_expert(training_rows(rows), total);
  const double ridge = choose_ridge(experts, total, "");
  auto result = tally(held_out_rows(rows), fit_readout(total, ridge));
  result.linear = true;
  result.ridge = ridge;
  return result;
}

TargetClassification linear_classify_leave_one_expert_out(const std::vector<EmbeddingRow>& rows) {
  NormalEquations total;
  const auto experts = rows_by_expert(training_rows(rows), total);
  std::map<std::string, Readout> readouts;  // each expert's, fit without it, its ridge chosen without it
  for (const auto& [id, e] : experts) {
    const NormalEquations others = total.minus(e.sums);
    readouts.emplace(id, fit_readout(others, choose_ridge(experts, others, id)));
  }
  auto result = tally(training_rows(rows), [&](const EmbeddingRow& q) { return readouts.at(q.expert_id)(q); });
  result.linear = true;
  result.leave_one_expert_out = true;
  return result;
}

namespace {

// "  expert ID (target T): C / N; nearest: A 40, B 12, C 8" with the three most frequent
// neighbours, or "; mean read-out +0.93" for the linear read-out; "targets -1/0/1" for a
// context-conditioned expert.
std::string expert_line(const std::string& id, const ExpertVote& e, bool linear) {
  std::string targets;
  for (double c : e.contexts) targets += (targets.empty() ? "" : "/") + exact_number(c);
  std::string line = "  expert " + id + (e.contexts.size() > 1 ? " (targets " : " (target ") + targets +
                     "): " + std::to_string(e.correct) + " / " + std::to_string(e.total);
  if (linear) return line + fmt::format("; mean read-out {:+.2f}\n", e.readout_sum / e.total);
  std::vector<std::pair<int, std::string>> by_count;
  for (const auto& [neighbour, n] : e.neighbours) by_count.push_back({-n, neighbour});
  std::sort(by_count.begin(), by_count.end());
  line += "; nearest:";
  for (size_t i = 0; i < std::min<size_t>(3, by_count.size()); ++i)
    line += (i ? ", " : " ") + by_count[i].second + " " + std::to_string(-by_count[i].first);
  return line + "\n";
}

}  // namespace

std::string format_classification(const TargetClassification& r, bool by_expert) {
  std::string rule = "k-NN (k = " + std::to_string(r.k) + ")";
  if (r.linear && r.leave_one_expert_out)
    rule = "linear read-out (its ridge chosen anew without each expert)";
  else if (r.linear)
    rule = fmt::format("linear read-out (ridge {:g}, chosen by leaving each training expert out)", r.ridge);
  std::string out = fmt::format(
      "{} on {}: {} / {} = {:.1f}%\n", rule,
      r.leave_one_expert_out ? "training embeddings, each expert left out in turn" : "held-out embeddings", r.correct,
      r.total, 100.0 * r.accuracy());
  for (const auto& [context, ct] : r.per_target)
    out += fmt::format("  target {:+g}: {} / {} = {:.1f}%\n", context, ct.first, ct.second, 100.0 * ct.first / ct.second);
  out += fmt::format("  experts with most of their rows correct: {} / {}\n", r.experts_majority_correct, r.experts);
  if (by_expert)
    for (const auto& [id, e] : r.per_expert) out += expert_line(id, e, r.linear);
  return out;
}

}  // namespace vaegail::eval
