// The desktop application's main window: the 3D scene in the centre, menus for files,
// studies, the simulation, analysis and help.
#pragma once

#include <QMainWindow>

namespace handlab::gui {

class PinchSimulation;
class SceneView;
class StudyPanel;

class MainWindow : public QMainWindow {
  Q_OBJECT

 public:
  explicit MainWindow(QWidget* parent = nullptr);
  SceneView* scene_view() const { return view_; }
  // Simulates the scripted pinch-and-lift of the current cube in the view, up to `until`
  // seconds (the script's end when 0); null when none runs.
  PinchSimulation* start_pinch(double until = 0.0);
  PinchSimulation* pinch() const { return pinch_; }
  void stop_pinch();  // the view returns to the static scene
  void set_show_contacts(bool show);

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
  void show_pinch_state();

  SceneView* view_ = nullptr;
  PinchSimulation* pinch_ = nullptr;
  bool show_contacts_ = false;
};

}  // namespace handlab::gui
