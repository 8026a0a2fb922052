#include "mocapdb_json/kriging_json.hpp"

#include "mocapdb/kriging/kriging.hpp"
#include "mocapdb/kriging/trend.hpp"

namespace mocapdb::json {

void write_variogram_model(JsonWriter& j, const kriging::VariogramModel& m) {
    j.begin_object();
    j.key("model").value(to_string(m.family));
    j.key("p").value(m.paper_p());
    j.key("nugget").value(m.nugget);
    j.key("sill").value(m.sill);
    j.key("range").value(m.range);
    j.end_object();
}

void write_variogram_fit(JsonWriter& j, const kriging::VariogramChoice& f, const std::string& weights) {
    j.begin_object();
    j.key("model").value(to_string(f.fit.model.family));
    j.key("p").value(f.fit.model.paper_p());
    j.key("nugget").value(f.fit.model.nugget);
    j.key("sill").value(f.fit.model.sill);
    j.key("range").value(f.fit.model.range);
    j.key("weights").value(weights);
    j.key("objective").value(f.fit.objective);
    j.key("converged").value(f.fit.converged);
    j.key("degenerate").value(f.fit.status == kriging::FitStatus::Degenerate);
    if (f.selection) {
        j.key("selection").begin_array();
        for (std::size_t k = 0; k < f.selection->grid.size(); ++k) {
            j.begin_object();
            j.key("p").value(f.selection->grid[k]);
            j.key("loo_mse").value(f.selection->loo_mse(static_cast<Eigen::Index>(k)));
            j.end_object();
        }
        j.end_array();
    }
    j.end_object();
}

void write_table_variogram(JsonWriter& j, const TableSettings& t, const kriging::ExperimentalVariogram& ev,
                           const std::optional<kriging::VariogramChoice>& fit) {
    j.begin_object();
    j.key("estimator").value(kriging::to_string(ev.estimator));
    j.key("trend").value(t.trend);
    j.key("normalized").value(t.normalized);
    j.key("cutoff").value(ev.cutoff);
    j.key("width").value(ev.width);
    j.key("max_distance").value(ev.max_distance);
    j.key("zero_distance_pairs").value(ev.zero_distance_pairs);
    j.key("bins").begin_array();
    for (int u = 0; u < ev.bins(); ++u) {
        j.begin_object();
        j.key("bin").value(u + 1);
        j.key("np").value(ev.npairs[static_cast<std::size_t>(u)]);
        j.key("dist").value(ev.dist(u));
        j.key("center").value(ev.center(u));
        j.key("gamma").value(ev.gamma(u));
        j.end_object();
    }
    j.end_array();
    if (fit) {
        j.key("fit");
        write_variogram_fit(j, *fit, t.weights);
    }
    j.end_object();
}

void write_table_kriging(JsonWriter& j, const TableSettings& t, const kriging::VariogramModel& model,
                         const std::optional<kriging::VariogramChoice>& fit, const kriging::ScalarTable& table,
                         const kriging::TableKriging& result) {
    const kriging::KrigingBatch& b = result.batch;
    const Eigen::VectorXd& pred = result.prediction;
    const std::optional<kriging::LooResult>& loo = result.loo;
    const kriging::KrigingStatus& st = result.status;
    j.begin_object();
    j.key("model");
    write_variogram_model(j, model);
    if (fit) {
        j.key("fit");
        write_variogram_fit(j, *fit, t.weights);
    }
    j.key("trend").value(t.trend);
    j.key("trend_fit").value(t.trend_fit);
    j.key("normalized").value(t.normalized);
    j.key("status").begin_object();
    j.key("factorization").value(kriging::to_string(st.factorization));
    j.key("jitter").value(st.jitter);
    j.key("rcond").value(st.rcond);
    j.key("duplicates_merged").value(static_cast<long long>(st.duplicates_merged));
    j.key("trend_rank_deficient").value(st.trend_rank_deficient);
    j.end_object();
    j.key("predictions").begin_array();
    for (Eigen::Index q = 0; q < pred.size(); ++q) {
        j.begin_object();
        j.key("row").value(static_cast<long long>(q + 1));
        j.key("prediction").value(pred(q));
        j.key("variance").value(b.variance(q));
        j.key("paper_variance").value(b.paper_variance(q));
        j.key("reliability").value(b.reliability(q));
        j.end_object();
    }
    j.end_array();
    if (loo) {
        j.key("loo").begin_object();
        j.key("mse").value(loo->mse);
        j.key("rows").begin_array();
        for (Eigen::Index i = 0; i < table.values.size(); ++i) {
            j.begin_object();
            j.key("row").value(static_cast<long long>(i + 1));
            j.key("observed").value(table.values(i));
            j.key("prediction").value(loo->prediction(i, 0));
            j.key("variance").value(loo->variance(i));
            j.key("residual").value(loo->residual(i, 0));
            j.key("zscore").value(loo->zscore(i, 0));
            j.end_object();
        }
        j.end_array();
        j.end_object();
    }
    j.end_object();
}

}  // namespace mocapdb::json
