// The desktop application's main window: the 3D scene in the centre, menus for files,
// studies, analysis and help.
#pragma once

#include <QMainWindow>

namespace handlab::gui {

class SceneView;
class StudyPanel;

class MainWindow : public QMainWindow {
  Q_OBJECT

 public:
  explicit MainWindow(QWidget* parent = nullptr);
  SceneView* scene_view() const { return view_; }

 private:
  void build_menus();
  void save_view_image();
  void set_cube_size(double metres);
  void open_csv_table();
  void open_study();

 public:
  // Shows the study database's progress in a dock; returns the error text (empty: opened).
  QString show_study(const QString& path);

 private:
  void show_about();

  SceneView* view_ = nullptr;
};

}  // namespace handlab::gui
