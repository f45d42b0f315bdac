// The accepted shapes and their indexes (ShapeDistributor::Impl::AcceptedShapes): vertex ->
// the shapes whose chart holds it, vertex -> the shapes with a part centre in a face of it.
#include "ShapeDistributorImpl.h"

namespace gs
{

void ShapeDistributor::Impl::AcceptedShapes::Reset(int vertices)
{
  Records.clear();
  Placed.clear();
  CoverIndex.assign(vertices, {});
  CentreIndex.assign(vertices, {});
}

int ShapeDistributor::Impl::AcceptedShapes::Add(
  Record&& r, const std::vector<int>& cover, const std::vector<int>& centres)
{
  const int id = static_cast<int>(Records.size());
  for (int v : cover)
  {
    CoverIndex[v].push_back(id);
  }
  for (int v : centres)
  {
    CentreIndex[v].push_back(id);
  }
  Placed.push_back(r.Shape);
  Records.push_back(std::move(r));
  return id;
}

ShapeDistributor::Impl::Record ShapeDistributor::Impl::AcceptedShapes::TakeLast(
  const std::vector<int>& cover, const std::vector<int>& centres)
{
  const int id = static_cast<int>(Records.size()) - 1;
  // (Add appended id last at each of its vertices.)
  auto drop = [id](std::vector<int>& ids) {
    if (!ids.empty() && ids.back() == id)
    {
      ids.pop_back();
    }
  };
  for (int v : cover)
  {
    drop(CoverIndex[v]);
  }
  for (int v : centres)
  {
    drop(CentreIndex[v]);
  }
  Record r = std::move(Records.back());
  Records.pop_back();
  Placed.pop_back();
  return r;
}

ShapeDistributor::Impl::Record ShapeDistributor::Impl::AcceptedShapes::Remove(
  int id, const std::vector<int>& cover, const std::vector<int>& centres)
{
  auto drop = [id](std::vector<int>& ids) {
    ids.erase(std::remove(ids.begin(), ids.end(), id), ids.end());
  };
  for (int v : cover)
  {
    drop(CoverIndex[v]);
  }
  for (int v : centres)
  {
    drop(CentreIndex[v]);
  }
  Record r = std::move(Records[id]);
  Records[id] = Record();
  return r;
}

void ShapeDistributor::Impl::AcceptedShapes::SortByKey(const std::vector<char>* removed)
{
  const int n = static_cast<int>(Records.size());
  std::vector<int> order;
  for (int i = 0; i < n; ++i)
  {
    if (!removed || !(*removed)[i])
    {
      order.push_back(i);
    }
  }
  std::stable_sort(
    order.begin(), order.end(), [this](int a, int b) { return Records[a].Key < Records[b].Key; });
  std::vector<int> newId(n, -1);
  std::vector<Record> sorted;
  sorted.reserve(order.size());
  for (std::size_t k = 0; k < order.size(); ++k)
  {
    newId[order[k]] = static_cast<int>(k);
    sorted.push_back(std::move(Records[order[k]]));
  }
  Records.swap(sorted);
  Placed.clear();
  for (const Record& r : Records)
  {
    Placed.push_back(r.Shape);
  }
  for (auto* index : { &CoverIndex, &CentreIndex })
  {
    for (std::vector<int>& ids : *index)
    {
      for (int& id : ids)
      {
        id = newId[id];
      }
    }
  }
}

} // namespace gs
